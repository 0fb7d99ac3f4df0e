// The progress bar under the Run button: stage name, percent and time left of the current stage.
// The worker reports a fraction per named stage, so the estimate is per stage: elapsed × (1 − f) / f.

export class ProgressBar {
  private stage = '';
  private stageStart = 0;
  private readonly fill: HTMLElement;
  private readonly label: HTMLElement;

  constructor(private readonly element: HTMLElement) {
    this.fill = element.querySelector<HTMLElement>('.progress-fill') ?? element;
    this.label = element.querySelector<HTMLElement>('.progress-label') ?? element;
    this.idle();
  }

  start(what: string): void {
    this.stage = '';
    this.element.dataset.state = 'running';
    this.element.hidden = false;
    this.show(0, `${what}: starting…`);
  }

  /** `fraction` is overall (0..1); `stageFraction` is the stage's own, for the time estimate. */
  update(fraction: number, stage: string, stageFraction: number, now = performance.now()): void {
    if (stage !== this.stage) {
      this.stage = stage;
      this.stageStart = now;
    }
    const elapsed = (now - this.stageStart) / 1000;
    let eta = '';
    if (stageFraction > 0.002 && stageFraction < 1 && elapsed > 0.75) {
      const left = (elapsed * (1 - stageFraction)) / stageFraction;
      eta = left < 1 ? ', under a second left' : `, about ${left < 90 ? `${Math.round(left)} s` : `${Math.round(left / 60)} min`} left`;
    }
    this.show(fraction, `${stage} — ${Math.round(stageFraction * 100)}%${eta}`);
  }

  idle(text = ''): void {
    this.element.dataset.state = 'idle';
    this.show(0, text);
  }

  private show(fraction: number, text: string): void {
    const clamped = Math.min(1, Math.max(0, fraction));
    this.fill.style.width = `${(clamped * 100).toFixed(1)}%`;
    this.element.setAttribute('aria-valuenow', String(Math.round(clamped * 100)));
    this.element.dataset.stage = this.stage;
    this.label.textContent = text;
  }
}
