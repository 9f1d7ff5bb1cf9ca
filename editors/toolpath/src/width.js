// Cuts with their real width: every cutting segment as a flat band of the tool diameter O
// in XY (at the segment's heights), with a disc at each move's ends for the round ends and
// corners, coloured as its move. What the top view shows is then the tool's footprint: the
// webs between cuts are the gaps.
import * as THREE from 'three';

/// `pts`: the moves as segments (geometry.js); `colourOf(i, out)`: the colour of move i.
export function widthGroup(moves, pts, diameter, colourOf) {
  const r = diameter / 2, c = new THREE.Color();
  const pos = [], col = [];
  for (let s = 0; s < pts.count; s++) {
    const i = pts.segMove[s];
    if (moves[i].kind === 'rapid') continue;
    const k = s * 6, x = pts.xyz;
    const dx = x[k + 3] - x[k], dy = x[k + 4] - x[k + 1], len = Math.hypot(dx, dy);
    if (len < 1e-9) continue;
    const nx = (-dy / len) * r, ny = (dx / len) * r;
    const a = [x[k] + nx, x[k + 1] + ny, x[k + 2]], b = [x[k] - nx, x[k + 1] - ny, x[k + 2]];
    const d = [x[k + 3] - nx, x[k + 4] - ny, x[k + 5]], e = [x[k + 3] + nx, x[k + 4] + ny, x[k + 5]];
    pos.push(...a, ...b, ...d, ...a, ...d, ...e);
    colourOf(i, c);
    for (let v = 0; v < 6; v++) col.push(c.r, c.g, c.b);
  }
  const geo = new THREE.BufferGeometry();
  geo.setAttribute('position', new THREE.BufferAttribute(new Float32Array(pos), 3));
  geo.setAttribute('color', new THREE.BufferAttribute(new Float32Array(col), 3));
  const mat = new THREE.MeshBasicMaterial({ vertexColors: true, side: THREE.DoubleSide, transparent: true, opacity: 0.55, depthWrite: false });
  const bands = new THREE.Mesh(geo, mat);
  // round ends: a disc at the end of every cutting move
  const cuts = [];
  moves.forEach((m, i) => { if (m.kind !== 'rapid') cuts.push(i); });
  const disc = new THREE.CircleGeometry(r, 20);
  const ends = new THREE.InstancedMesh(disc, new THREE.MeshBasicMaterial({ transparent: true, opacity: 0.55, depthWrite: false }), Math.max(cuts.length, 1));
  ends.count = cuts.length;
  const mat4 = new THREE.Matrix4();
  cuts.forEach((i, n) => {
    const t = moves[i].to;
    mat4.makeTranslation(t[0], t[1], t[2]);
    ends.setMatrixAt(n, mat4);
    ends.setColorAt(n, colourOf(i, c));
  });
  const group = new THREE.Group();
  group.name = 'tool width';
  group.add(bands, ends);
  return group;
}
