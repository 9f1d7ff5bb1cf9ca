// The toolpath viewer: the moves of one program in 3-D (three.js), coloured by depth or kind,
// with the tool moving along them, tied to the source through each move's element and
// G-code line. Data: the JSON of `millpath_ide::toolpath` (embedded, posted by VS Code, or
// served by the Neovim plugin's local server).
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { paths, positionAt, cumulative, moveAt } from './geometry.js';
import { boundsWithClamps, clampGroup, HIT_COLOUR, CLAMP_COLOUR } from './clamps.js';
import { CutPart, cutColour } from './cut.js';
import { widthGroup } from './width.js';
import { t as say, setCurrent, translatePage } from './words.js';

const t0 = performance.now();
const KIND_COLOURS = {
  mill: '#1f77b4', mark: '#e377c2', bars: '#ff7f0e', drill: '#d62728', helix: '#9467bd', rapid: '#8a8a8a', probe: '#2ca02c',
};
const HIGHLIGHT = new THREE.Color('#ff00aa');
const vscode = typeof acquireVsCodeApi === 'function' ? acquireVsCodeApi() : null;
const served = location.protocol === 'http:' || location.protocol === 'https:';
const $ = (id) => document.getElementById(id);

const stage = $('stage');
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio || 1);
stage.prepend(renderer.domElement);
const scene = new THREE.Scene();
const camera = new THREE.OrthographicCamera(-1, 1, 1, -1, -1e5, 1e5);
camera.up.set(0, 0, 1);
const controls = new OrbitControls(camera, renderer.domElement);
controls.screenSpacePanning = true;
controls.zoomToCursor = true;

const st = {
  data: null, world: null, extent: 1, centre: new THREE.Vector3(), cum: null, total: 0,
  time: 0, playing: false, speed: 20, selected: [], hover: -1, colour: 'depth',
  segFrom: null, segMove: null, segCount: 0, drawn: 0,
  // the cut part follows the playback once it is used; before, it shows the finished part
  cutFollows: false, showCut: true, showWidth: false, feeds: { min: 0, max: 0 },
};

// ---- drawing on demand ----
let pending = false;
function requestDraw() {
  if (pending) return;
  pending = true;
  requestAnimationFrame(draw);
}
function draw() {
  pending = false;
  resize();
  performance.mark('mp-draw0');
  renderer.render(scene, camera);
  performance.mark('mp-draw1');
  placeLabels();
  if (st.playing) tick();
}
controls.addEventListener('change', requestDraw);
new ResizeObserver(requestDraw).observe(stage);
function resize() {
  const w = stage.clientWidth || 1, h = stage.clientHeight || 1;
  const size = renderer.getSize(new THREE.Vector2());
  if (size.x !== w || size.y !== h) renderer.setSize(w, h, false);
  const aspect = w / h, half = st.extent * 0.6;
  camera.left = -half * aspect; camera.right = half * aspect; camera.top = half; camera.bottom = -half;
  camera.updateProjectionMatrix();
}

// ---- theme: VS Code's variables inside its webview, else the OS ----
function themeColours() {
  const cs = getComputedStyle(document.body);
  const bg = new THREE.Color();
  bg.setStyle(cs.backgroundColor || '#1e1e1e');
  const fg = new THREE.Color();
  fg.setStyle(cs.color || '#dddddd');
  return { bg, fg };
}
function applyTheme() {
  const { bg } = themeColours();
  renderer.setClearColor(bg, 1);
  if (st.world) st.world.grid.material.color = gridColour();
  requestDraw();
}
function gridColour() {
  const { bg, fg } = themeColours();
  return bg.clone().lerp(fg, 0.18);
}
new MutationObserver(applyTheme).observe(document.body, { attributes: true, attributeFilter: ['class', 'style'] });
new MutationObserver(applyTheme).observe(document.documentElement, { attributes: true, attributeFilter: ['class', 'style'] });
matchMedia('(prefers-color-scheme: dark)').addEventListener('change', applyTheme);

// ---- colours ----
function depthColour(z, b, out) {
  const span = b.maxZ - b.minZ;
  const t = span > 0 ? Math.max(0, Math.min(1, (b.maxZ - z) / span)) : 1;
  // shallow: blue, deep: red
  return out.setHSL((220 - 220 * t) / 360, 0.8, 0.47);
}
/// Feed colour: slow blue to fast red over the cuts' feeds.
function feedColour(f, out) {
  const { min, max } = st.feeds;
  const t = max > min ? Math.max(0, Math.min(1, (f - min) / (max - min))) : 0.5;
  return out.setHSL((240 - 240 * t) / 360, 0.85, 0.45);
}
function moveColour(m, b, out) {
  if (m.kind === 'rapid') return out.set(KIND_COLOURS.rapid);
  if (st.colour === 'kind') return out.set(KIND_COLOURS[m.kind] || KIND_COLOURS.mill);
  if (st.colour === 'feed') return feedColour(Number(m.feed) || 0, out);
  return depthColour(Math.min(m.from[2], m.to[2]), b, out);
}

// ---- the scene of one program ----
function disposeWorld() {
  if (!st.world) return;
  scene.remove(st.world.group);
  st.world.group.traverse((o) => {
    if (o.geometry) o.geometry.dispose();
    if (o.material) o.material.dispose();
  });
  st.world = null;
}

function build(data) {
  disposeWorld();
  const b = data.bounds;
  const group = new THREE.Group();
  const moves = data.moves;
  const pts = paths(moves);
  const cutFeeds = moves.filter((m) => m.kind !== 'rapid').map((m) => Number(m.feed) || 0);
  st.feeds = { min: cutFeeds.length ? Math.min(...cutFeeds.slice(0, 200000)) : 0, max: cutFeeds.length ? Math.max(...cutFeeds.slice(0, 200000)) : 0 };
  st.segFrom = pts.segFrom; st.segMove = pts.segMove; st.segCount = pts.count;
  // cuts and rapids: one geometry each (a 100,000-move program is two draw calls)
  const cutPos = new Float32Array(pts.count * 6), cutCol = new Float32Array(pts.count * 6);
  const rapPos = new Float32Array(pts.count * 6);
  let nc = 0, nr = 0;
  const c = new THREE.Color();
  const seen = new Uint8Array(moves.length);
  for (let s = 0; s < pts.count; s++) {
    const i = pts.segMove[s], m = moves[i], k = s * 6;
    seen[i] = 1;
    if (m.kind === 'rapid') {
      rapPos.set(pts.xyz.subarray(k, k + 6), nr * 6); nr++;
    } else {
      moveColour(m, b, c);
      cutPos.set(pts.xyz.subarray(k, k + 6), nc * 6);
      cutCol.set([c.r, c.g, c.b, c.r, c.g, c.b], nc * 6); nc++;
    }
  }
  st.drawn = seen.reduce((a, v) => a + v, 0);
  const cutGeo = new THREE.BufferGeometry();
  cutGeo.setAttribute('position', new THREE.BufferAttribute(cutPos.subarray(0, nc * 6), 3));
  cutGeo.setAttribute('color', new THREE.BufferAttribute(cutCol.subarray(0, nc * 6), 3));
  const cuts = new THREE.LineSegments(cutGeo, new THREE.LineBasicMaterial({ vertexColors: true }));
  const rapGeo = new THREE.BufferGeometry();
  rapGeo.setAttribute('position', new THREE.BufferAttribute(rapPos.subarray(0, nr * 6), 3));
  const rapids = new THREE.LineSegments(rapGeo, new THREE.LineDashedMaterial({ color: KIND_COLOURS.rapid, dashSize: 1, gapSize: 1, transparent: true, opacity: 0.8 }));
  rapids.computeLineDistances();
  group.add(cuts, rapids);

  // the view's extent: the moves and the clamps
  const vb = boundsWithClamps(b, data.clamps);
  const w = Math.max(vb.maxX - vb.minX, 1), h = Math.max(vb.maxY - vb.minY, 1);
  const extent = Math.max(w, h, vb.maxZ - vb.minZ, 10);
  st.extent = extent * 1.15;
  rapids.material.dashSize = rapids.material.gapSize = extent / 150;
  st.centre.set((vb.minX + vb.maxX) / 2, (vb.minY + vb.maxY) / 2, (vb.minZ + vb.maxZ) / 2);

  // grid in mm at Z 0 over the drawing and the origin, lines on multiples of the step
  const step = Math.pow(10, Math.max(0, Math.floor(Math.log10(extent / 4))));
  const x0 = Math.floor(Math.min(b.minX, 0) / step) * step - step, x1 = Math.ceil(Math.max(b.maxX, 0) / step) * step + step;
  const y0 = Math.floor(Math.min(b.minY, 0) / step) * step - step, y1 = Math.ceil(Math.max(b.maxY, 0) / step) * step + step;
  const gl = [];
  for (let x = x0; x <= x1 + 1e-9 && gl.length < 6000; x += step) gl.push(x, y0, 0, x, y1, 0);
  for (let y = y0; y <= y1 + 1e-9 && gl.length < 12000; y += step) gl.push(x0, y, 0, x1, y, 0);
  const gridGeo = new THREE.BufferGeometry();
  gridGeo.setAttribute('position', new THREE.BufferAttribute(new Float32Array(gl), 3));
  const grid = new THREE.LineSegments(gridGeo, new THREE.LineBasicMaterial({ color: gridColour(), transparent: true, opacity: 0.8 }));
  group.add(grid);
  st.gridStep = step;
  $('grid-label').textContent = say('grid', step);
  group.add(new THREE.AxesHelper(Math.max(step, extent / 8)));

  // the stock top T as a translucent plane over the drawing
  const T = data.stock && data.stock.top;
  // (the cut part, when there is one, is the stock itself)
  if (typeof T === 'number' && !(data.cut && data.cut.nx)) {
    const pad = extent * 0.05;
    const plane = new THREE.Mesh(new THREE.PlaneGeometry(w + 2 * pad, h + 2 * pad),
      new THREE.MeshBasicMaterial({ color: '#c8a165', transparent: true, opacity: 0.16, side: THREE.DoubleSide, depthWrite: false }));
    plane.position.set((b.minX + b.maxX) / 2, (b.minY + b.maxY) / 2, T);
    group.add(plane);
  }

  // the height map: a measured surface coloured by height (colours from the data), or the
  // probe points of a grid not measured yet at the nominal top
  const hm = data.heightmap;
  document.body.dataset.surface = '';
  if (hm && Array.isArray(hm.xs) && Array.isArray(hm.ys)) {
    const nx = hm.xs.length, ny = hm.ys.length, pos = [], col = [], hc = new THREE.Color();
    for (let j = 0; j < ny; j++) {
      for (let i = 0; i < nx; i++) {
        pos.push(hm.xs[i], hm.ys[j], hm.z[j][i]);
        hc.set(hm.colours[j][i]);
        col.push(hc.r, hc.g, hc.b);
      }
    }
    const nodes = new THREE.BufferGeometry();
    nodes.setAttribute('position', new THREE.BufferAttribute(new Float32Array(pos), 3));
    nodes.setAttribute('color', new THREE.BufferAttribute(new Float32Array(col), 3));
    const points = new THREE.Points(nodes, new THREE.PointsMaterial({ vertexColors: true, size: 7, sizeAttenuation: false, depthTest: false, transparent: true }));
    points.renderOrder = 5; // over the translucent stock top and surface
    group.add(points);
    if (hm.measured && nx > 1 && ny > 1) {
      const idx = [];
      for (let j = 0; j + 1 < ny; j++) {
        for (let i = 0; i + 1 < nx; i++) {
          const a = j * nx + i, b2 = a + 1, c2 = a + nx, d2 = c2 + 1;
          idx.push(a, b2, d2, a, d2, c2);
        }
      }
      const sg = new THREE.BufferGeometry();
      sg.setAttribute('position', nodes.getAttribute('position'));
      sg.setAttribute('color', nodes.getAttribute('color'));
      sg.setIndex(idx);
      // drawn first and blended without the transparent pass, so every move lies over it
      const surface = new THREE.Mesh(sg, new THREE.MeshBasicMaterial({
        vertexColors: true, opacity: 0.8, side: THREE.DoubleSide, depthWrite: false, depthTest: false,
        blending: THREE.CustomBlending, blendSrc: THREE.SrcAlphaFactor, blendDst: THREE.OneMinusSrcAlphaFactor,
      }));
      surface.renderOrder = -1;
      group.add(surface);
    }
    document.body.dataset.surface = `${hm.measured ? 'measured' : 'grid'} ${nx}x${ny}`;
  }

  // the cut part: the stock after the program (data from Rust), cut during playback
  let cutPart = null;
  document.body.dataset.cut = '';
  if (data.cut && data.cut.nx && data.cut.ny) {
    cutPart = new CutPart(data.cut, moves);
    cutPart.group.visible = st.showCut;
    group.add(cutPart.group);
    document.body.dataset.cut = `${data.cut.nx}x${data.cut.ny}`;
  }

  // clamps and the moves that run into them
  const cl = clampGroup(data, pts, 9);
  group.add(cl.group);
  st.hits = cl.hits;
  document.body.dataset.clamps = String(cl.boxes);
  document.body.dataset.clampHits = String(cl.hits.length);

  // start, end and turn markers, direction arrows
  const r = extent / 120;
  const marker = (p, colour, geo) => {
    const mesh = new THREE.Mesh(geo, new THREE.MeshBasicMaterial({ color: colour }));
    mesh.position.set(p[0], p[1], p[2]);
    group.add(mesh);
    return mesh;
  };
  if (moves.length) {
    marker(data.start || moves[0].from, '#2ca02c', new THREE.SphereGeometry(r, 16, 12)).name = 'start';
    marker(moves[moves.length - 1].to, '#d62728', new THREE.BoxGeometry(r * 1.6, r * 1.6, r * 1.6)).name = 'end';
  }
  const arrows = [], turns = [];
  let prev = null;
  for (let i = 0; i < moves.length; i++) {
    const m = moves[i];
    if (m.kind === 'rapid' || m.arc) { prev = null; continue; }
    const d = [m.to[0] - m.from[0], m.to[1] - m.from[1], m.to[2] - m.from[2]];
    const len = Math.hypot(d[0], d[1], d[2]);
    if (len < 1e-9) continue;
    const u = [d[0] / len, d[1] / len, d[2] / len];
    if (prev && u[0] * prev[0] + u[1] * prev[1] + u[2] * prev[2] < -0.9 && turns.length < 2000) turns.push(m.from);
    prev = u;
    if (len > extent / 40 && arrows.length < 3000) arrows.push([m, u]);
  }
  const cone = new THREE.ConeGeometry(r * 0.7, r * 2.2, 10);
  const arrowMesh = new THREE.InstancedMesh(cone, new THREE.MeshBasicMaterial({ color: '#ffffff' }), Math.max(arrows.length, 1));
  arrowMesh.count = arrows.length;
  const mat = new THREE.Matrix4(), q = new THREE.Quaternion(), yAxis = new THREE.Vector3(0, 1, 0);
  arrows.forEach(([m, u], k) => {
    q.setFromUnitVectors(yAxis, new THREE.Vector3(u[0], u[1], u[2]));
    mat.compose(new THREE.Vector3((m.from[0] + m.to[0]) / 2, (m.from[1] + m.to[1]) / 2, (m.from[2] + m.to[2]) / 2), q, new THREE.Vector3(1, 1, 1));
    arrowMesh.setMatrixAt(k, mat);
    arrowMesh.setColorAt(k, moveColour(m, b, c));
  });
  group.add(arrowMesh);
  const oct = new THREE.OctahedronGeometry(r * 0.9);
  const turnMesh = new THREE.InstancedMesh(oct, new THREE.MeshBasicMaterial({ color: '#ffbf00' }), Math.max(turns.length, 1));
  turnMesh.count = turns.length;
  turns.forEach((p, k) => { mat.makeTranslation(p[0], p[1], p[2]); turnMesh.setMatrixAt(k, mat); });
  group.add(turnMesh);

  // probes: points sized in screen pixels, labels as HTML
  const probes = data.probes || [];
  if (probes.length) {
    const pg = new THREE.BufferGeometry();
    pg.setAttribute('position', new THREE.BufferAttribute(new Float32Array(probes.flatMap((p) => [p.x, p.y, p.z ?? 0])), 3));
    group.add(new THREE.Points(pg, new THREE.PointsMaterial({ color: KIND_COLOURS.probe, size: 8, sizeAttenuation: false })));
  }
  $('labels').replaceChildren(...probes.map((p) => {
    const s = document.createElement('span');
    s.textContent = p.name;
    s.dataset.probe = p.name;
    return s;
  }));

  // the tool: a cylinder of diameter O with its tip at the programmed point
  const dia = (data.tool && data.tool.diameter) || extent / 50;
  const len = Math.max(dia * 3, extent / 12);
  const toolGeo = new THREE.CylinderGeometry(dia / 2, dia / 2, len, 24);
  toolGeo.rotateX(Math.PI / 2);
  toolGeo.translate(0, 0, len / 2);
  const tool = new THREE.Mesh(toolGeo, new THREE.MeshBasicMaterial({ color: '#c0c0c0', transparent: true, opacity: 0.55, depthWrite: false }));
  group.add(tool);

  // the selection, drawn over everything
  const hlGeo = new THREE.BufferGeometry();
  const hl = new THREE.LineSegments(hlGeo, new THREE.LineBasicMaterial({ color: HIGHLIGHT, depthTest: false }));
  hl.renderOrder = 10;
  const hlPoints = new THREE.Points(hlGeo, new THREE.PointsMaterial({ color: HIGHLIGHT, size: 5, sizeAttenuation: false, depthTest: false }));
  hlPoints.renderOrder = 10;
  group.add(hl, hlPoints);

  scene.add(group);
  st.world = { group, grid, tool, hl, cuts, pts, cutPart, width: null };
  if (st.showWidth) showWidth(true);
}

/// Cuts drawn with the tool's diameter (built when first asked for, rebuilt on recolouring).
function showWidth(on) {
  st.showWidth = on;
  const w = st.world;
  if (!w) return;
  if (w.width) {
    w.group.remove(w.width);
    w.width.traverse((o) => { if (o.geometry) o.geometry.dispose(); if (o.material) o.material.dispose(); });
    w.width = null;
  }
  if (on) {
    const d = st.data, dia = (d.tool && d.tool.diameter) || 1;
    w.width = widthGroup(d.moves, w.pts, dia, (i, out) => moveColour(d.moves[i], d.bounds, out));
    w.group.add(w.width);
  }
  document.body.dataset.toolWidth = on ? '1' : '';
  requestDraw();
}

function recolour() {
  if (!st.world) return;
  if (st.showWidth) showWidth(true);
  const b = st.data.bounds, c = new THREE.Color(), moves = st.data.moves;
  const col = st.world.cuts.geometry.getAttribute('color');
  let n = 0;
  for (let s = 0; s < st.segCount; s++) {
    const m = moves[st.segMove[s]];
    if (m.kind === 'rapid') continue;
    moveColour(m, b, c);
    col.array.set([c.r, c.g, c.b, c.r, c.g, c.b], n * 6);
    n++;
  }
  col.needsUpdate = true;
  legend();
  requestDraw();
}

// ---- legend and statistics ----
function legend() {
  const d = st.data, b = d.bounds, counts = {};
  for (const m of d.moves) counts[m.kind] = (counts[m.kind] || 0) + 1;
  if ((d.probes || []).length) counts.probe = d.probes.length;
  const kinds = Object.keys(KIND_COLOURS).filter((k) => counts[k]);
  const f3 = (v) => v.toFixed(3);
  const el = $('legend');
  el.innerHTML = '';
  const row = document.createElement('div');
  row.className = 'kinds';
  for (const k of kinds) {
    const s = document.createElement('span');
    s.dataset.kind = k;
    s.innerHTML = `<span class="sw" style="background:${KIND_COLOURS[k]}"></span>${kindWord(k)} ${counts[k]}`;
    row.append(s);
  }
  el.append(row);
  if (st.colour === 'depth') {
    const dep = document.createElement('div');
    dep.className = 'depth';
    const cv = document.createElement('canvas');
    cv.width = 120; cv.height = 10;
    const g = cv.getContext('2d'), c = new THREE.Color();
    for (let x = 0; x < 120; x++) {
      depthColour(b.maxZ - (x / 119) * (b.maxZ - b.minZ), b, c);
      g.fillStyle = `#${c.getHexString()}`;
      g.fillRect(x, 0, 1, 10);
    }
    dep.append(`Z ${f3(b.maxZ)}`, cv, `${f3(b.minZ)} mm`);
    el.append(dep);
  }
  if (st.colour === 'feed') {
    const fd = document.createElement('div');
    fd.className = 'feed';
    const cv = document.createElement('canvas');
    cv.width = 120; cv.height = 10;
    const g = cv.getContext('2d'), c = new THREE.Color(), { min, max } = st.feeds;
    for (let x = 0; x < 120; x++) {
      feedColour(min + (x / 119) * (max - min), c);
      g.fillStyle = `#${c.getHexString()}`;
      g.fillRect(x, 0, 1, 10);
    }
    fd.append(`F ${min.toFixed(0)}`, cv, `${max.toFixed(0)} mm/min`);
    el.append(fd);
  }
  if (d.cut && d.cut.nx) {
    const cp = document.createElement('div');
    cp.className = 'cut';
    const cv = document.createElement('canvas');
    cv.width = 120; cv.height = 10;
    const g = cv.getContext('2d'), c = new THREE.Color();
    for (let x = 0; x < 120; x++) {
      cutColour(d.cut.top - (x / 119) * (d.cut.top - d.cut.lowest), d.cut.top, d.cut.lowest, c);
      g.fillStyle = `#${c.getHexString()}`;
      g.fillRect(x, 0, 1, 10);
    }
    const note = [d.cut.coarsened ? say('coarsened') : '', d.cut.thinned ? say('finalSteps') : ''].filter(Boolean).join(', ');
    cp.append(say('cut', d.cut.nx, d.cut.ny, f3(d.cut.cell), f3(d.cut.top)), cv, `${f3(d.cut.lowest)} mm${note ? ` (${note})` : ''}`);
    el.append(cp);
  }
  const hm = d.heightmap;
  if (hm && Array.isArray(hm.xs)) {
    const sf = document.createElement('div');
    sf.className = 'surface';
    const n = `${hm.xs.length}×${hm.ys.length}`;
    if (hm.measured) {
      const cv = document.createElement('canvas');
      cv.width = 120; cv.height = 10;
      const g = cv.getContext('2d'), grad = g.createLinearGradient(0, 0, 120, 0);
      hm.legend.ramp.forEach((col, k) => grad.addColorStop(k / (hm.legend.ramp.length - 1), col));
      g.fillStyle = grad;
      g.fillRect(0, 0, 120, 10);
      sf.append(say('surface', n, f3(hm.legend.min)), cv, `${f3(hm.legend.max)} mm`);
    } else {
      sf.textContent = say('heightMap', n, f3(hm.top));
    }
    el.append(sf);
  }
  if ((d.clamps || []).length) {
    const cl = document.createElement('div');
    cl.className = 'clamps';
    const hits = st.hits || [];
    cl.innerHTML = `<span class="sw" style="background:${CLAMP_COLOUR}"></span>${say('clamps', d.clamps.length)}` +
      (hits.length ? ` · <span class="sw" style="background:${HIT_COLOUR}"></span><b>${say('intoClamp', hits.length)}</b>` : ` · ${say('noClampTouched')}`);
    el.append(cl);
  }
  const tool = d.tool ? say('tool', f3(d.tool.diameter)) : '';
  const stock = d.stock ? say('stock', f3(d.stock.top)) : '';
  const extra = document.createElement('div');
  extra.textContent = [tool, stock].filter(Boolean).join(' · ');
  el.append(extra);
}

// ---- playback ----
// h:mm:ss.s, as millpath writes every exact time (h:mm:ss)
function fmtTime(s) {
  const tenths = Math.round(Math.max(0, Number.isFinite(s) ? s : 0) * 10);
  const h = Math.floor(tenths / 36000), m = Math.floor(tenths / 600) % 60, r = (tenths % 600) / 10;
  return `${h}:${m < 10 ? '0' : ''}${m}:${r < 10 ? '0' : ''}${r.toFixed(1)}`;
}
function setTime(t, follow = true) {
  if (!st.data || !st.world) return null;
  st.time = Math.max(0, Math.min(st.total, t));
  const { index, point } = positionAt(st.data.moves, st.cum, st.time);
  // the cut part: the moves done by now (the one running is done at its end)
  if (follow) st.cutFollows = true;
  const cp = st.world.cutPart;
  if (cp && st.cutFollows) {
    const at = st.data.moves[index], doneNow = at && point.every((v, k) => Math.abs(v - at.to[k]) < 1e-9);
    cp.showUpTo(st.time >= st.total ? st.data.moves.length : index + (doneNow ? 1 : 0));
    document.body.dataset.cutMoves = String(cp.movesShown());
  }
  const m = st.data.moves[index];
  st.world.tool.position.set(point[0], point[1], point[2]);
  st.world.tool.visible = true;
  $('scrub').value = String(st.time);
  const f3 = (v) => v.toFixed(3);
  $('readout').textContent = `X ${f3(point[0])} Y ${f3(point[1])} Z ${f3(point[2])}  ` +
    `F ${m ? (m.kind === 'rapid' ? say('rapidFeed') : f3(m.feed)) : '-'}  ${say('line')} ${m ? m.line : '-'}  ` +
    `${fmtTime(st.time)} / −${fmtTime(st.total - st.time)}`;
  document.body.dataset.time = String(st.time);
  requestDraw();
  return { index, point };
}
let lastTick = 0;
function tick() {
  const now = performance.now();
  const dt = lastTick ? (now - lastTick) / 1000 : 0;
  lastTick = now;
  if (st.time >= st.total) { pause(); return; }
  setTime(st.time + dt * st.speed);
}
function play() {
  if (st.time >= st.total) st.time = 0;
  st.playing = true; lastTick = 0;
  $('play').textContent = '❚❚';
  requestDraw();
}
function pause() {
  st.playing = false;
  $('play').textContent = '▶';
}
$('play').addEventListener('click', () => (st.playing ? pause() : play()));
$('speed').addEventListener('change', (e) => { st.speed = Number(e.target.value); });
$('scrub').addEventListener('input', (e) => { pause(); setTime(Number(e.target.value)); });
window.addEventListener('keydown', (e) => {
  if (e.code === 'Space' && e.target === document.body) { e.preventDefault(); st.playing ? pause() : play(); }
});

// ---- camera presets ----
function setView(name) {
  const c = st.centre, d = st.extent * 4;
  // top: a hair south of straight above, so that Y points up on the screen
  const dirs = { top: [0, -1e-4, 1], front: [0, -1, 0], side: [1, 0, 0], iso: [1, -1, 1] };
  const v = new THREE.Vector3(...(dirs[name] || dirs.iso)).normalize().multiplyScalar(d);
  camera.position.copy(c).add(v);
  camera.zoom = 1;
  controls.target.copy(c);
  camera.lookAt(c);
  controls.update();
  document.querySelectorAll('[data-view]').forEach((b) => b.classList.toggle('on', b.dataset.view === name));
  requestDraw();
}
document.querySelectorAll('[data-view]').forEach((b) => b.addEventListener('click', () => setView(b.dataset.view)));
$('colour').addEventListener('change', (e) => { st.colour = e.target.value; recolour(); });
$('cut-on').addEventListener('change', (e) => {
  st.showCut = e.target.checked;
  if (st.world && st.world.cutPart) st.world.cutPart.group.visible = st.showCut;
  requestDraw();
});
$('width-on').addEventListener('change', (e) => showWidth(e.target.checked));

// ---- picking in screen space: the move nearest the pointer within 6 px ----
const proj = new THREE.Matrix4();
function pick(clientX, clientY) {
  if (!st.world) return -1;
  const rect = renderer.domElement.getBoundingClientRect();
  const px = clientX - rect.left, py = clientY - rect.top, w = rect.width, h = rect.height;
  proj.multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse);
  const e = proj.elements, xyz = st.world.pts.xyz;
  const sx = (x, y, z) => ((e[0] * x + e[4] * y + e[8] * z + e[12]) + 1) / 2 * w;
  const sy = (x, y, z) => (1 - (e[1] * x + e[5] * y + e[9] * z + e[13])) / 2 * h;
  let best = -1, bestD = 36, bestRapid = true;
  for (let s = 0; s < st.segCount; s++) {
    const k = s * 6;
    const ax = sx(xyz[k], xyz[k + 1], xyz[k + 2]), ay = sy(xyz[k], xyz[k + 1], xyz[k + 2]);
    const bx = sx(xyz[k + 3], xyz[k + 4], xyz[k + 5]), by = sy(xyz[k + 3], xyz[k + 4], xyz[k + 5]);
    const dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
    const t = l2 > 0 ? Math.max(0, Math.min(1, ((px - ax) * dx + (py - ay) * dy) / l2)) : 0;
    const qx = ax + t * dx - px, qy = ay + t * dy - py, d2 = qx * qx + qy * qy;
    const i = st.segMove[s], rapid = st.data.moves[i].kind === 'rapid';
    // cuts win over rapids at the same place
    if (d2 < bestD - 1 || (d2 <= bestD + 1 && bestRapid && !rapid)) { best = i; bestD = d2; bestRapid = rapid; }
  }
  return best;
}
function sourceOf(m) {
  const s = m && m.source;
  return typeof s === 'number' ? (st.data.sources || [])[s] || null : s || null;
}
function describe(i) {
  const m = st.data.moves[i], s = sourceOf(m);
  const where = s ? `${s.label}  ${s.text || ''}` : say('noSource');
  const clamps = (m.hits || []).map((k) => ((st.data.clamps || [])[k] || {}).name).filter(Boolean);
  const into = clamps.length ? `\n⚠ ${say('runsIntoClamp', clamps.map((n) => `'${n}'`).join(', '))}` : '';
  return `${say('move', i + 1, st.data.moves.length, kindWord(m.kind))}  ${where}\n${say('gcodeLine', m.line)}: ${m.gcode || ''}${into}`;
}
function showHighlight(indices) {
  st.selected = indices;
  const w = st.world;
  if (!w) return;
  const chosen = new Set(indices), out = [];
  for (let s = 0; s < st.segCount; s++) {
    if (chosen.has(st.segMove[s])) for (let k = 0; k < 6; k++) out.push(w.pts.xyz[s * 6 + k]);
  }
  w.hl.geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(out), 3));
  w.hl.geometry.computeBoundingSphere();
  document.body.dataset.highlighted = String(indices.length);
  requestDraw();
}
function select(i) {
  if (!st.data || !st.data.moves[i]) return;
  const m = st.data.moves[i], s = sourceOf(m);
  showHighlight([i]);
  $('info').textContent = describe(i);
  document.body.dataset.selectedSource = s ? s.label : '';
  document.body.dataset.selectedLine = String(m.line);
  const msg = { type: 'reveal', index: i, source: s, gcodeLine: m.line };
  if (vscode) vscode.postMessage(msg);
  if (served) fetch('/click', { method: 'POST', body: JSON.stringify(msg) }).catch(() => {});
  window.dispatchEvent(new CustomEvent('millpath-select', { detail: msg }));
}
/// The moves of the element at `file`:`line` (0-based), or of the G-code line `gcodeLine`.
function highlight({ file, line, gcodeLine }) {
  if (!st.data) return [];
  const moves = st.data.moves, sources = st.data.sources || [];
  let wanted;
  if (typeof gcodeLine === 'number') {
    const m = moves.find((mv) => mv.line === gcodeLine);
    wanted = m ? new Set([m.source]) : new Set();
  } else {
    const norm = (p) => String(p || '').replace(/\\/g, '/');
    wanted = new Set(sources.map((s, k) => (norm(s.file) === norm(file) && s.line === line ? k : -1)).filter((k) => k >= 0));
  }
  const hits = [];
  moves.forEach((m, i) => { if (typeof m.source === 'number' && wanted.has(m.source)) hits.push(i); });
  showHighlight(hits);
  if (hits.length) $('info').textContent = `${say('moves', hits.length)}  ${describe(hits[0])}`;
  return hits;
}

let hoverQueued = null;
renderer.domElement.addEventListener('pointermove', (e) => {
  if (e.buttons) return;
  if (!hoverQueued) requestAnimationFrame(() => {
    const { x, y } = hoverQueued; hoverQueued = null;
    const i = pick(x, y);
    if (i !== st.hover) {
      st.hover = i;
      renderer.domElement.style.cursor = i >= 0 ? 'pointer' : '';
      if (i >= 0) $('info').textContent = describe(i);
    }
  });
  hoverQueued = { x: e.clientX, y: e.clientY };
});
let down = null;
renderer.domElement.addEventListener('pointerdown', (e) => { down = [e.clientX, e.clientY]; });
renderer.domElement.addEventListener('click', (e) => {
  // a drag (orbit, pan) is no click
  if (down && Math.hypot(e.clientX - down[0], e.clientY - down[1]) > 4) return;
  const i = pick(e.clientX, e.clientY);
  if (i >= 0) select(i);
});

// ---- probe labels in screen pixels ----
function placeLabels() {
  const d = st.data;
  if (!d || !(d.probes || []).length) return;
  const spans = $('labels').children, v = new THREE.Vector3();
  const w = stage.clientWidth, h = stage.clientHeight;
  d.probes.forEach((p, k) => {
    v.set(p.x, p.y, p.z ?? 0).project(camera);
    spans[k].style.left = `${((v.x + 1) / 2) * w}px`;
    spans[k].style.top = `${((1 - v.y) / 2) * h}px`;
  });
}

// ---- language ----
function kindWord(k) {
  return say('kinds')[k] || k;
}
/// Puts the page in `lang`; `redraw`: the words drawn from the data too (the legend, the
/// grid, the readout and the info line).
let shownLang = null;
function useLang(lang, redraw) {
  const before = shownLang;
  shownLang = setCurrent(lang);
  // the same language again (each new data has it): the page's lines stay as they are
  if (shownLang === before) return;
  translatePage();
  if (!st.data || !st.data.moves || !st.data.moves.length) {
    $('title').textContent = say('title');
    return;
  }
  if (!redraw) return;
  if (st.gridStep !== undefined) $('grid-label').textContent = say('grid', st.gridStep);
  legend();
  setTime(st.time, false);
}

// ---- data in ----
function render(data, keepView) {
  if (data && data.lang) useLang(data.lang, false);
  st.data = data;
  const empty = $('empty');
  if (empty) empty.remove();
  if (!data || !data.moves || !data.moves.length) {
    disposeWorld();
    $('title').textContent = say('title');
    const div = document.createElement('div');
    div.id = 'empty';
    div.textContent = `${say('none')}${data && data.error ? `: ${data.error}` : ''}`;
    stage.append(div);
    document.body.dataset.moves = '0';
    requestDraw();
    return;
  }
  $('title').textContent = `${data.path || ''}${data.file ? `  —  ${data.file.split(/[\\/]/).pop()}` : ''}`;
  // placeholder machine settings in use (`compile` would ask for them)
  if (data.warnings && data.warnings.length) $('title').textContent += `  ⚠ ${data.warnings.join('; ')}`;
  performance.mark('mp-build0');
  build(data);
  performance.mark('mp-build1');
  st.cum = cumulative(data.moves);
  st.total = st.cum[st.cum.length - 1];
  $('scrub').max = String(st.total);
  $('stats').textContent = (data.stats || []).join('\n');
  legend();
  applyTheme();
  if (!keepView) { setView('iso'); st.cutFollows = false; }
  setTime(keepView ? st.time : 0, false);
  document.body.dataset.moves = String(st.drawn);
  // ready once the first frame of this data is drawn
  requestAnimationFrame(() => requestAnimationFrame(() => {
    // since navigation start: parsing the page and its data, three.js, the first frame
    document.body.dataset.ready = String(performance.now());
    document.body.dataset.readyScript = String(performance.now() - t0);
  }));
}

window.addEventListener('message', (ev) => {
  const m = ev.data;
  if (!m) return;
  if (m.type === 'toolpath') render(m.data, st.data && m.data && st.data.path === m.data.path);
  if (m.type === 'select' && typeof m.index === 'number') select(m.index);
  if (m.type === 'highlight') highlight(m);
});

// ---- the page served by the Neovim plugin: follow the buffer ----
if (served) {
  let version = null;
  const poll = async () => {
    try {
      const r = await fetch('/data', { cache: 'no-store', headers: version ? { 'If-None-Match': version } : {} });
      if (r.status === 200) {
        version = r.headers.get('ETag');
        const data = await r.json();
        render(data, st.data && data && st.data.path === data.path);
      }
      const h = await fetch('/highlight', { cache: 'no-store' });
      if (h.status === 200) {
        const want = await h.json();
        if (want && want.seq !== st.highlightSeq) { st.highlightSeq = want.seq; highlight(want); }
      }
    } catch (_) { /* the editor went away: keep the last picture */ }
    setTimeout(poll, 700);
  };
  poll();
}

// for tests and embedding pages
window.millpathToolpath = {
  render, select, highlight, setView, setTime,
  /// The page's language, 'en' or 'de' (the data's `lang` sets it too).
  setLang: (lang) => useLang(lang, true),
  lang: () => document.documentElement.lang,
  data: () => st.data,
  highlighted: () => st.selected.slice(),
  play, pause,
  drawnMoves: () => st.drawn,
  /// Indexes of the moves drawn in red: they run into a clamp.
  clampHits: () => (st.hits || []).slice(),
  /// The cut part as shown: its lowest height, the height at (x, y), how many moves it shows.
  cutLowest: () => (st.world && st.world.cutPart ? st.world.cutPart.lowestShown() : null),
  cutHeightAt: (x, y) => (st.world && st.world.cutPart ? st.world.cutPart.heightAt(x, y) : null),
  cutMoves: () => (st.world && st.world.cutPart ? st.world.cutPart.movesShown() : null),
  showCut: (on) => { $('cut-on').checked = on; $('cut-on').dispatchEvent(new Event('change')); },
  showToolWidth: (on) => { $('width-on').checked = on; showWidth(on); },
  setColour: (c) => { $('colour').value = c; st.colour = c; recolour(); },
  duration: () => st.total,
  toolPosition: () => (st.world ? st.world.tool.position.toArray() : null),
  cameraMatrix: () => { camera.updateMatrixWorld(); return [...camera.projectionMatrix.elements, ...camera.matrixWorldInverse.elements]; },
  /// Client coordinates of the model point `p` [x, y, z].
  screenOfPoint: (p) => {
    const v = new THREE.Vector3(p[0], p[1], p[2]).project(camera);
    const rect = renderer.domElement.getBoundingClientRect();
    return [rect.left + ((v.x + 1) / 2) * rect.width, rect.top + ((1 - v.y) / 2) * rect.height];
  },
  /// Client coordinates of the point at fraction `f` of move `i` (for clicking it).
  screenOf: (i, f = 0.5) => {
    const p = moveAt(st.data.moves[i], f);
    const v = new THREE.Vector3(p[0], p[1], p[2]).project(camera);
    const rect = renderer.domElement.getBoundingClientRect();
    return [rect.left + ((v.x + 1) / 2) * rect.width, rect.top + ((1 - v.y) / 2) * rect.height];
  },
};

useLang(navigator.language, false);
applyTheme();
// a narrow view (a webview beside the source) starts with the panel folded
if (stage.clientWidth < 600) $('side').open = false;
const embedded = JSON.parse($('toolpath-data').textContent || 'null');
if (embedded) render(embedded);
else { const d = document.createElement('div'); d.id = 'empty'; d.dataset.t = 'noneYet'; d.textContent = say('noneYet'); stage.append(d); }
if (vscode) vscode.postMessage({ type: 'ready' });
