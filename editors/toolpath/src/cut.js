// The cut part: the stock after the program as a shaded 3-D height field, coloured by depth,
// cut move by move during playback. Everything comes computed from Rust (`cut` of the data:
// the checker's height field and its lowerings grouped by G-code line, base64 arrays); the
// page only puts the heights into a mesh.
import * as THREE from 'three';

/// A base64 field as a typed array (little endian, as written).
export function decode(b64, Type) {
  const bin = atob(b64 || '');
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  return new Type(bytes.buffer, 0, bytes.length / Type.BYTES_PER_ELEMENT);
}

/// Depth colour of the cut part: uncut stock tan, then light blue (shallow) to red (deepest).
export function cutColour(z, top, lowest, out) {
  const span = top - lowest;
  if (top - z <= 1e-4 || span <= 0) return out.setRGB(0.86, 0.78, 0.62);
  const t = Math.max(0, Math.min(1, (top - z) / span));
  return out.setHSL((200 - 200 * t) / 360, 0.6, 0.62 - 0.14 * t);
}

export class CutPart {
  /// `cut`: the data's cut part; `moves`: the data's moves (their G-code lines place the
  /// lowerings in time).
  constructor(cut, moves) {
    this.cut = cut;
    const { nx, ny } = cut;
    this.n = nx * ny;
    this.final = decode(cut.heights, Float32Array);
    this.cells = decode(cut.cells, Uint32Array);
    this.z = decode(cut.z, Float32Array);
    const lines = decode(cut.lines, Uint32Array), counts = decode(cut.counts, Uint32Array);
    // each group of lowerings: the first move of its line, and where its events start
    const moveOfLine = new Map();
    moves.forEach((m, i) => { if (!moveOfLine.has(m.line)) moveOfLine.set(m.line, i); });
    this.groupMove = new Int32Array(lines.length);
    this.groupStart = new Uint32Array(lines.length + 1);
    for (let g = 0; g < lines.length; g++) {
      this.groupMove[g] = moveOfLine.has(lines[g]) ? moveOfLine.get(lines[g]) : moves.length;
      this.groupStart[g + 1] = this.groupStart[g] + counts[g];
    }
    this.lowest = cut.lowest;
    const pos = new Float32Array(this.n * 3), col = new Float32Array(this.n * 3);
    for (let j = 0; j < ny; j++) {
      for (let i = 0; i < nx; i++) {
        const k = (j * nx + i) * 3;
        pos[k] = cut.x0 + (i + 0.5) * cut.cell;
        pos[k + 1] = cut.y0 + (j + 0.5) * cut.cell;
      }
    }
    const idx = new Uint32Array(Math.max(nx - 1, 0) * Math.max(ny - 1, 0) * 6);
    let t = 0;
    for (let j = 0; j + 1 < ny; j++) {
      for (let i = 0; i + 1 < nx; i++) {
        const a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
        idx[t++] = a; idx[t++] = b; idx[t++] = d; idx[t++] = a; idx[t++] = d; idx[t++] = c;
      }
    }
    const geo = new THREE.BufferGeometry();
    geo.setAttribute('position', new THREE.BufferAttribute(pos, 3));
    geo.setAttribute('color', new THREE.BufferAttribute(col, 3));
    geo.setIndex(new THREE.BufferAttribute(idx, 1));
    // flat shading from the triangles' own slopes: no normals to keep up to date
    const mat = new THREE.MeshLambertMaterial({
      vertexColors: true, flatShading: true, side: THREE.DoubleSide,
      polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
    });
    this.mesh = new THREE.Mesh(geo, mat);
    this.mesh.name = 'cut part';
    this.group = new THREE.Group();
    this.group.add(this.mesh, new THREE.AmbientLight(0xffffff, 1.1));
    const sun = new THREE.DirectionalLight(0xffffff, 1.6);
    sun.position.set(-1, -2, 3);
    this.group.add(sun);
    this.heights = new Float32Array(this.n);
    this.applied = -1;
    this.showAll();
  }

  setHeight(k, z, c) {
    const pos = this.mesh.geometry.getAttribute('position').array;
    const col = this.mesh.geometry.getAttribute('color').array;
    this.heights[k] = z;
    pos[k * 3 + 2] = z;
    cutColour(z, this.cut.top, this.lowest, c);
    col[k * 3] = c.r; col[k * 3 + 1] = c.g; col[k * 3 + 2] = c.b;
  }

  touch() {
    const g = this.mesh.geometry;
    g.getAttribute('position').needsUpdate = true;
    g.getAttribute('color').needsUpdate = true;
    g.computeBoundingSphere();
  }

  /// The stock after the whole program.
  showAll() {
    const c = new THREE.Color();
    for (let k = 0; k < this.n; k++) this.setHeight(k, this.final[k], c);
    this.applied = this.groupMove.length;
    this.done = Infinity;
    this.touch();
  }

  /// The stock after the moves before `moveIndex` (the moves that are done).
  showUpTo(moveIndex) {
    if (moveIndex === this.done) return;
    const c = new THREE.Color();
    if (moveIndex < this.done) {
      for (let k = 0; k < this.n; k++) this.setHeight(k, this.cut.top, c);
      this.applied = 0;
    }
    let g = this.applied;
    for (; g < this.groupMove.length && this.groupMove[g] < moveIndex; g++) {
      for (let e = this.groupStart[g]; e < this.groupStart[g + 1]; e++) this.setHeight(this.cells[e], this.z[e], c);
    }
    this.applied = g;
    this.done = moveIndex;
    this.touch();
  }

  /// How many moves (from the first) the shown stock has been cut by.
  movesShown() {
    return Number.isFinite(this.done) ? this.done : null;
  }

  /// The lowest height shown, and the height of the cell at (x, y).
  lowestShown() {
    let z = Infinity;
    for (let k = 0; k < this.n; k++) if (this.heights[k] < z) z = this.heights[k];
    return z;
  }
  heightAt(x, y) {
    const { x0, y0, cell, nx, ny } = this.cut;
    const i = Math.floor((x - x0) / cell), j = Math.floor((y - y0) / cell);
    if (i < 0 || j < 0 || i >= nx || j >= ny) return null;
    return this.heights[j * nx + i];
  }
}
