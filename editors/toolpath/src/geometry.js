// Moves as polylines, and where the tool is at a time: plain functions over the data of
// `millpath_ide::toolpath`, shared by the drawing, the picking and the playback.

const TAU = 2 * Math.PI;

/// The angle swept by an arc move (0 < sweep ≤ 2π; a move back to its start is a full circle).
function sweepOf(m) {
  const a = m.arc, f = m.from, t = m.to;
  const a0 = Math.atan2(f[1] - a.cy, f[0] - a.cx), a1 = Math.atan2(t[1] - a.cy, t[0] - a.cx);
  let s = a.ccw ? a1 - a0 : a0 - a1;
  while (s <= 1e-9) s += TAU;
  while (s > TAU + 1e-9) s -= TAU;
  return { a0, s };
}

/// The point at fraction `f` (0…1) of move `m`: arcs turn around their centre (climbing
/// linearly in Z for helixes), lines are straight.
export function moveAt(m, f) {
  const p = m.from, q = m.to;
  if (!m.arc) return [p[0] + (q[0] - p[0]) * f, p[1] + (q[1] - p[1]) * f, p[2] + (q[2] - p[2]) * f];
  const { a0, s } = sweepOf(m), a = m.arc;
  const r0 = Math.hypot(p[0] - a.cx, p[1] - a.cy), r1 = Math.hypot(q[0] - a.cx, q[1] - a.cy);
  const ang = a0 + (a.ccw ? 1 : -1) * s * f, r = r0 + (r1 - r0) * f;
  return [a.cx + r * Math.cos(ang), a.cy + r * Math.sin(ang), p[2] + (q[2] - p[2]) * f];
}

/// Every move as line segments: `xyz` (6 floats a segment), `segMove` (its move), `count`.
/// Each move has at least one segment (a move without length: a point), so every move is drawn
/// and can be picked.
export function paths(moves) {
  let count = 0;
  const pieces = new Int32Array(moves.length);
  for (let i = 0; i < moves.length; i++) {
    const m = moves[i];
    pieces[i] = m.arc ? Math.min(48, Math.max(2, Math.ceil(sweepOf(m).s / (Math.PI / 24)))) : 1;
    count += pieces[i];
  }
  const xyz = new Float32Array(count * 6), segMove = new Int32Array(count);
  let s = 0;
  for (let i = 0; i < moves.length; i++) {
    const m = moves[i], n = pieces[i];
    let prev = m.from;
    for (let k = 1; k <= n; k++) {
      const next = k === n ? m.to : moveAt(m, k / n);
      xyz.set([prev[0], prev[1], prev[2], next[0], next[1], next[2]], s * 6);
      segMove[s++] = i;
      prev = next;
    }
  }
  return { xyz, segMove, count };
}

/// Start times: `cum[i]` is when move i begins, `cum[n]` the program's duration (seconds of
/// the statistics' model).
export function cumulative(moves) {
  const cum = new Float64Array(moves.length + 1);
  for (let i = 0; i < moves.length; i++) {
    const t = Number(moves[i].t);
    cum[i + 1] = cum[i] + (Number.isFinite(t) && t > 0 ? t : 0);
  }
  return cum;
}

/// The move running at time `t` and the tool's position then.
export function positionAt(moves, cum, t) {
  const n = moves.length;
  if (!n) return { index: -1, point: [0, 0, 0] };
  if (t <= 0) return { index: 0, point: moves[0].from.slice() };
  if (t >= cum[n]) return { index: n - 1, point: moves[n - 1].to.slice() };
  // the last move starting at or before t that takes time
  let lo = 0, hi = n - 1;
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (cum[mid] <= t) lo = mid; else hi = mid - 1;
  }
  while (lo > 0 && cum[lo + 1] - cum[lo] <= 0) lo--;
  const dt = cum[lo + 1] - cum[lo];
  return { index: lo, point: moveAt(moves[lo], dt > 0 ? Math.min(1, (t - cum[lo]) / dt) : 1) };
}
