// The progress bar of a run: stage name, percent and time left of the current stage. The worker
// reports a fraction per named stage; a step without one (sending the mesh to the worker) shows
// its name only, with the bar sweeping.
//
// Time left: the mean shift's fraction does not grow evenly (the first vertices build the charts
// that later ones reuse, and many points settle in a few steps), so an estimate from the stage's
// start read "21%, about 10 s left" for a run that ended 0.7 s later (issue 30). The estimate uses
// the rate of the last RATE_WINDOW_S seconds, and is shown only once the stage has run a while and
// the estimate stayed steady (two estimates in a row within a factor of 1.5), never for a stage
// that is about to end anyway.

/**
 * Stages whose fraction is of an upper bound: the default denoiser races its candidates and stops
 * when its risk estimate rises (core/src/denoise_default.cpp reports passes run over the most it
 * may run), so "17%" ended the run and no time left can be read from it.
 */
const OPEN_ENDED = ['denoise passes'];

/** Seconds of recent progress the rate is measured over. */
const RATE_WINDOW_S = 1.5;
/** No estimate before a stage has run this long (s). */
const SETTLE_S = 1.5;
/** Estimates below this are not worth a word (s). */
const SHORTEST_S = 2;

export class ProgressBar {
  private stage = '';
  private stageStart = 0;
  /** (time s, stage fraction) of the current stage, the last RATE_WINDOW_S seconds of it. */
  private samples: Array<[number, number]> = [];
  private lastEstimate = Number.NaN;
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

  /**
   * `fraction` is overall (0..1); `stageFraction` is the stage's own, for the time estimate, or
   * null for a step that cannot say how far it is.
   */
  update(fraction: number, stage: string, stageFraction: number | null, now = performance.now()): void {
    const t = now / 1000;
    if (stage !== this.stage) {
      this.stage = stage;
      this.stageStart = t;
      this.samples = [];
      this.lastEstimate = Number.NaN;
    }
    if (stageFraction === null) {
      this.element.dataset.state = 'preparing';
      this.show(fraction, `${stage}…`);
      return;
    }
    this.element.dataset.state = 'running';
    if (OPEN_ENDED.some((name) => stage.endsWith(name))) {
      this.show(fraction, `${stage}… (until the estimated error stops falling)`);
      return;
    }
    this.samples.push([t, stageFraction]);
    while (this.samples.length > 2 && t - this.samples[0]![0] > RATE_WINDOW_S) this.samples.shift();
    const eta = this.estimate(t, stageFraction);
    this.show(fraction, `${stage} — ${Math.round(stageFraction * 100)}%${eta}`);
  }

  idle(text = ''): void {
    this.element.dataset.state = 'idle';
    this.stage = '';
    this.show(0, text);
  }

  /** ", about 12 s left", or '' while there is no steady estimate worth showing. */
  private estimate(t: number, f: number): string {
    const [t0, f0] = this.samples[0]!;
    const rate = (f - f0) / Math.max(t - t0, 1e-9);
    if (!(rate > 0) || f >= 1 || t - this.stageStart < SETTLE_S) return '';
    const left = (1 - f) / rate;
    const steady = this.lastEstimate / left < 1.5 && left / this.lastEstimate < 1.5;
    this.lastEstimate = left;
    if (!steady || left < SHORTEST_S) return '';
    return `, about ${left < 90 ? `${Math.round(left)} s` : `${Math.round(left / 60)} min`} left`;
  }

  private show(fraction: number, text: string): void {
    const clamped = Math.min(1, Math.max(0, fraction));
    this.fill.style.width = `${(clamped * 100).toFixed(1)}%`;
    this.element.setAttribute('aria-valuenow', String(Math.round(clamped * 100)));
    this.element.dataset.stage = this.stage;
    this.label.textContent = text;
  }
}
