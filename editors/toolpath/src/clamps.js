// Clamps and fixtures in the view: the `[[clamp]]` boxes of millpath.toml (data.clamps) as
// translucent boxes with edges, and the moves that run into one (their `hits`, found by the
// compiler's check) in red over everything. The page only draws what the data says.
import * as THREE from 'three';

export const CLAMP_COLOUR = '#d4a017';
export const HIT_COLOUR = '#ff1a1a';

/// The view's bounds grown by the boxes (so a clamp beside the drawing is in the picture).
export function boundsWithClamps(b, clamps) {
  const out = { ...b };
  for (const c of clamps || []) {
    out.minX = Math.min(out.minX, c.min[0]); out.maxX = Math.max(out.maxX, c.max[0]);
    out.minY = Math.min(out.minY, c.min[1]); out.maxY = Math.max(out.maxY, c.max[1]);
    out.minZ = Math.min(out.minZ, c.min[2]); out.maxZ = Math.max(out.maxZ, c.max[2]);
  }
  return out;
}

/// Indexes of the moves that touch a clamp.
export function hitMoves(moves) {
  const out = [];
  moves.forEach((m, i) => { if (Array.isArray(m.hits) && m.hits.length) out.push(i); });
  return out;
}

/// The boxes and the red hits as one group; `pts`: the moves as segments (geometry.js).
export function clampGroup(data, pts, markSize) {
  const group = new THREE.Group();
  const clamps = data.clamps || [];
  const hits = hitMoves(data.moves);
  const struck = new Set(hits.flatMap((i) => data.moves[i].hits));
  clamps.forEach((c, k) => {
    const size = [0, 1, 2].map((a) => Math.max(c.max[a] - c.min[a], 1e-6));
    const geo = new THREE.BoxGeometry(size[0], size[1], size[2]);
    const colour = struck.has(k) ? HIT_COLOUR : CLAMP_COLOUR;
    const box = new THREE.Mesh(geo, new THREE.MeshBasicMaterial({ color: colour, transparent: true, opacity: 0.22, depthWrite: false }));
    const edges = new THREE.LineSegments(new THREE.EdgesGeometry(geo), new THREE.LineBasicMaterial({ color: colour }));
    for (const o of [box, edges]) {
      o.position.set((c.min[0] + c.max[0]) / 2, (c.min[1] + c.max[1]) / 2, (c.min[2] + c.max[2]) / 2);
      o.name = `clamp ${c.name}`;
      group.add(o);
    }
  });
  if (hits.length) {
    const chosen = new Set(hits), xyz = [], mids = [];
    for (let s = 0; s < pts.count; s++) {
      if (chosen.has(pts.segMove[s])) for (let k = 0; k < 6; k++) xyz.push(pts.xyz[s * 6 + k]);
    }
    for (const i of hits) {
      const m = data.moves[i];
      mids.push((m.from[0] + m.to[0]) / 2, (m.from[1] + m.to[1]) / 2, (m.from[2] + m.to[2]) / 2);
    }
    const lg = new THREE.BufferGeometry();
    lg.setAttribute('position', new THREE.BufferAttribute(new Float32Array(xyz), 3));
    const lines = new THREE.LineSegments(lg, new THREE.LineBasicMaterial({ color: HIT_COLOUR, depthTest: false, transparent: true }));
    const pg = new THREE.BufferGeometry();
    pg.setAttribute('position', new THREE.BufferAttribute(new Float32Array(mids), 3));
    const marks = new THREE.Points(pg, new THREE.PointsMaterial({ color: HIT_COLOUR, size: markSize, sizeAttenuation: false, depthTest: false, transparent: true }));
    lines.renderOrder = marks.renderOrder = 9;
    group.add(lines, marks);
  }
  return { group, hits, boxes: clamps.length, struck: struck.size };
}
