// Live plots (uPlot) over the last WINDOW_S seconds: wake-up latency and misses from the core's
// statistics (10 Hz), the force the controller renders on the handle (each state frame), and the
// client's round trip from the demo's scene messages.
import uPlot from './vendor/uplot/uPlot.esm.js';

const WINDOW_S = 30;
const OPEN_BUCKET_US = 20000; // drawn for "beyond 10 ms" (the histogram's open bucket)

class RollingPlot {
  constructor(element, title, series, axes) {
    this.data = [[], ...series.map(() => [])];
    const width = Math.max(element.clientWidth, 280);
    this.plot = new uPlot({
      width,
      height: 170,
      title,
      scales: { x: { time: false } },
      series: [{ label: 't (s)' }, ...series],
      axes: [{ stroke: '#8d97a5', grid: { stroke: '#2a3039' } }, ...axes],
      legend: { live: false },
    }, this.data, element);
    new ResizeObserver(() => this.plot.setSize({ width: Math.max(element.clientWidth, 280), height: 170 }))
      .observe(element);
  }

  add(t, values) {
    this.data[0].push(t);
    values.forEach((v, i) => this.data[i + 1].push(v));
    while (this.data[0].length > 0 && this.data[0][0] < t - WINDOW_S) {
      this.data.forEach((column) => column.shift());
    }
  }

  redraw() {
    this.plot.setData(this.data);
  }

  get points() {
    return this.data[0].length;
  }
}

const axis = (label, side = 3) => ({ label, side, stroke: '#8d97a5', grid: { stroke: '#2a3039' } });

export class Plots {
  constructor() {
    this.start = performance.now();
    this.latency = new RollingPlot(document.getElementById('plot-latency'), '', [
      { label: 'worst wake, 100 ms (≤ µs)', stroke: '#f0c040', scale: 'us' },
      { label: 'p99 since start (µs)', stroke: '#3d8bfd', scale: 'us' },
      { label: 'misses', stroke: '#d23b3b', scale: 'n', paths: uPlot.paths.bars?.({ size: [0.6, 6] }) },
    ], [{ ...axis('µs'), scale: 'us', size: 64 }, { ...axis('misses', 1), scale: 'n', grid: { show: false } }]);
    this.force = new RollingPlot(document.getElementById('plot-force'), '', [
      { label: 'rendered |F| (N)', stroke: '#ff4fd8', width: 2 },
      { label: 'Fx', stroke: '#e06c6c' },
      { label: 'Fy', stroke: '#6cd68a' },
      { label: 'Fz', stroke: '#6c9be0' },
      { label: 'operator |F| (N)', stroke: '#f0c040', dash: [6, 4] },
    ], [axis('N')]);
    this.rtt = new RollingPlot(document.getElementById('plot-rtt'), '', [
      { label: 'last (ms)', stroke: '#40d0ff' },
      { label: 'mean (ms)', stroke: '#3d8bfd', width: 2 },
    ], [axis('ms')]);
    this.lastSceneSteps = -1;
  }

  now() {
    return (performance.now() - this.start) / 1000;
  }

  /** Adds one state frame's samples. */
  add(frame) {
    const t = this.now();
    const { stats, arm, scene } = frame;
    if (stats) {
      const worst = stats.interval.wake_max_us_at_most;
      this.latency.add(t, [worst < 0 ? OPEN_BUCKET_US : worst || null, stats.wake_latency.p99_ns / 1e3, stats.interval.misses]);
    }
    if (arm) {
      const f = arm.rendered_wrench;
      const o = arm.operator_wrench;
      this.force.add(t, [Math.hypot(f[0], f[1], f[2]), f[0], f[1], f[2], Math.hypot(o[0], o[1], o[2])]);
    }
    if (scene && scene.steps !== this.lastSceneSteps) {
      this.lastSceneSteps = scene.steps;
      this.rtt.add(t, [scene.rtt_last_us / 1000, scene.rtt_mean_us / 1000]);
    }
  }

  redraw() {
    this.latency.redraw();
    this.force.redraw();
    this.rtt.redraw();
  }

  /** Points held per plot (for tests and the curious). */
  counts() {
    return { latency: this.latency.points, force: this.force.points, rtt: this.rtt.points };
  }
}
