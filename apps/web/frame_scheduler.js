// Progressive refinement, driven by the client: while the user drags, cheap
// preview frames (half size, twice the ray step, lower JPEG quality); once
// nothing has changed for a moment, one full-quality frame. At most one frame
// is in flight: requests made meanwhile collapse into the latest one, so a
// slow server never builds up a backlog of stale frames.
// A third kind, 'refine', is the next frame of a progressive technique
// (pathtrace, whose estimate grows while nothing changes): asked for only
// when nothing else is waiting, and any change takes its place.

const SETTLE_MS = 220;

export class FrameScheduler {
  // render(kind) -> Promise; kind is 'preview', 'full' or 'refine'.
  constructor(render) {
    this.render = render;
    this.inFlight = false;
    this.pending = null;
    this.settleTimer = null;
  }

  // A change while interacting: a preview now, a full frame when it settles.
  preview() {
    this.pending = 'preview';
    clearTimeout(this.settleTimer);
    this.settleTimer = setTimeout(() => { this.settleTimer = null; this.full(); }, SETTLE_MS);
    this.pump();
  }

  // A finished change (mouse released, value committed): a full frame.
  full() {
    clearTimeout(this.settleTimer);
    this.settleTimer = null;
    this.pending = 'full';
    this.pump();
  }

  // One more frame of the unchanged scene, unless a change is waiting.
  refine() {
    if (this.pending || this.settleTimer) return;
    this.pending = 'refine';
    this.pump();
  }

  idle() { return !this.inFlight && !this.pending && !this.settleTimer; }

  async pump() {
    if (this.inFlight || !this.pending) return;
    const kind = this.pending;
    this.pending = null;
    this.inFlight = true;
    try {
      await this.render(kind);
    } finally {
      this.inFlight = false;
      this.pump();
    }
  }
}
