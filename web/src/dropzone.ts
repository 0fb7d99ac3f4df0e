// Drag and drop of a file anywhere on the page, with an overlay while a file is over the page.

function carriesFiles(event: DragEvent): boolean {
  return event.dataTransfer?.types.includes('Files') ?? false;
}

/**
 * Calls onFile with the first dropped file. The overlay is shown while files are dragged over
 * target; text or links dragged around the page are left to the browser.
 */
export function installDropZone(target: HTMLElement, overlay: HTMLElement, onFile: (file: File) => void): void {
  // dragenter/dragleave fire for every child element crossed, so count them instead of toggling.
  let depth = 0;
  const hide = (): void => {
    depth = 0;
    overlay.hidden = true;
  };
  target.addEventListener('dragenter', (event) => {
    if (!carriesFiles(event)) return;
    event.preventDefault();
    depth++;
    overlay.hidden = false;
  });
  target.addEventListener('dragover', (event) => {
    if (!carriesFiles(event)) return;
    // Without preventDefault the browser would open the file itself instead of firing 'drop'.
    event.preventDefault();
    if (event.dataTransfer) event.dataTransfer.dropEffect = 'copy';
  });
  target.addEventListener('dragleave', (event) => {
    if (!carriesFiles(event)) return;
    depth = Math.max(0, depth - 1);
    if (depth === 0) overlay.hidden = true;
  });
  target.addEventListener('drop', (event) => {
    if (!carriesFiles(event)) return;
    event.preventDefault();
    hide();
    const file = event.dataTransfer?.files[0];
    if (file) onFile(file);
  });
}
