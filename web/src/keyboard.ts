// Keyboard access to the two actions people repeat while trying settings: Ctrl+Enter (⌘+Enter on
// a Mac) runs the preset, Esc cancels a running filter. They work from anywhere on the page,
// parameter fields included, and do nothing while their button is disabled.

export function installShortcuts(run: HTMLButtonElement, cancel: HTMLButtonElement): void {
  // Capture phase: lil-gui stops keydown events of its fields from bubbling.
  document.addEventListener('keydown', (event) => {
    if (event.key === 'Enter' && (event.ctrlKey || event.metaKey) && !event.altKey) {
      if (run.disabled) return;
      event.preventDefault();
      run.click();
    } else if (event.key === 'Escape') {
      if (cancel.disabled) return;
      event.preventDefault();
      cancel.click();
    }
  }, { capture: true });
}
