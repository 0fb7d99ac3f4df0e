// On narrow screens (phones) the filter panel is a sheet over the lower part of the view, closed
// until the person opens it with the bar's "Filters" button, so the view keeps the screen. The
// layout itself is CSS (style.css, the max-width media query); this only keeps the open state.

export function installSheet(toggle: HTMLButtonElement, onToggle: () => void = () => undefined): void {
  const set = (open: boolean) => {
    document.body.dataset.sheet = open ? 'open' : 'closed';
    toggle.setAttribute('aria-expanded', String(open));
    toggle.textContent = open ? 'Hide filters' : 'Filters';
    onToggle();
  };
  toggle.addEventListener('click', () => set(document.body.dataset.sheet !== 'open'));
  set(false);
}
