// SPDX-License-Identifier: MIT
// fbrl-station's page (docs/page.md). The station sends the cell (GET /api/scene), the methods
// (GET /api/methods) and, over the WebSocket /ws, each reading of the arm with its chain of joint
// points as the library computes it (fbrl_arm_chain): this file only draws what it is sent.
// Lengths are inches in the arm's frame (x forward, y left, z up), as the cell files give them.
'use strict';

const COLOURS = { box: 0xb8b8b8, cylinder: 0xc8a070, keepout: 0xff6060, table: 0xe2dccb, place: 0x2060d0,
                  rack: 0x20a040, arm: 0xf0a020, joint: 0x505050, tool: 0xff00ff, background: 0xf4f6f8 };
const ESTIMATED_AFTER_S = 1.5; // a reading older than this (or the arm moving) is an estimate
const ARM_RADII = [1.0, 0.9, 0.7, 0.3]; // base-shoulder, upper arm, forearm, wrist-tool (drawing only)

const page = window.fbrlPage = { ready: false, delays: [], poses: 0, errors: [], marks: { script: performance.now() } };
const $ = (id) => document.getElementById(id);
let scene3, camera, renderer, controls, armGroup, toolMark, labels = [], centre, span;
let methods = [], ws = null, me = null, controlBy = null, lastPose = null, armState = 'Disconnected';
let currentRun = null;

// ------------------------------------------------------------------ the 3-D view
function v3(p) { return new THREE.Vector3(p[0], p[1], p[2]); }

function addLabel(text, at, cls) {
  const div = document.createElement('div');
  div.className = 'label ' + cls;
  div.textContent = text;
  $('labels').appendChild(div);
  labels.push({ div, at: v3(at) });
}

function edges(mesh, colour) {
  const l = new THREE.LineSegments(new THREE.EdgesGeometry(mesh.geometry), new THREE.LineBasicMaterial({ color: colour }));
  l.position.copy(mesh.position);
  l.quaternion.copy(mesh.quaternion);
  return l;
}

function obstacle(o) {
  let mesh;
  const transparent = o.kind === 'keepout';
  const mat = new THREE.MeshBasicMaterial({ color: COLOURS[o.kind], transparent, opacity: transparent ? 0.35 : 1,
                                            depthWrite: !transparent });
  if (o.kind === 'cylinder') {
    const h = o.hi[2] - o.lo[2];
    mesh = new THREE.Mesh(new THREE.CylinderGeometry(o.r, o.r, h, 32), mat);
    mesh.rotation.x = Math.PI / 2; // three's cylinders stand on y; the cell's on z
    mesh.position.set(o.c[0], o.c[1], o.lo[2] + h / 2);
  } else {
    const s = [0, 1, 2].map((i) => o.hi[i] - o.lo[i]);
    mesh = new THREE.Mesh(new THREE.BoxGeometry(s[0], s[1], s[2]), mat);
    mesh.position.set((o.lo[0] + o.hi[0]) / 2, (o.lo[1] + o.hi[1]) / 2, (o.lo[2] + o.hi[2]) / 2);
  }
  mesh.name = o.name;
  let top = [(o.lo[0] + o.hi[0]) / 2, (o.lo[1] + o.hi[1]) / 2, o.hi[2]];
  if (o.placed) { // carried by its block's calibration, p = r p_taught + t, as the guard carries it
    const r = o.placed.r, t = o.placed.t;
    const m = new THREE.Matrix4().set(r[0][0], r[0][1], r[0][2], t[0], r[1][0], r[1][1], r[1][2], t[1],
                                      r[2][0], r[2][1], r[2][2], t[2], 0, 0, 0, 1);
    mesh.updateMatrix();
    m.multiply(mesh.matrix).decompose(mesh.position, mesh.quaternion, mesh.scale);
    top = [0, 1, 2].map((i) => r[i][0] * top[0] + r[i][1] * top[1] + r[i][2] * top[2] + t[i]);
  }
  scene3.add(mesh);
  scene3.add(edges(mesh, transparent ? 0xc00000 : 0x333333));
  addLabel(o.name + (o.block ? ' (on ' + o.block + ')' : ''), top, o.kind);
}

function buildScene(s) {
  scene3 = new THREE.Scene();
  scene3.background = new THREE.Color(COLOURS.background);
  const lo = [-6, -6, 0], hi = [6, 6, 20]; // the arm's base and some of its height, always in view
  const grow = (p) => { for (let i = 0; i < 3; i++) { lo[i] = Math.min(lo[i], p[i]); hi[i] = Math.max(hi[i], p[i]); } };
  // framed on what stands in the cell: a keep-out zone (the operator's side) may reach far past it
  s.obstacles.filter((o) => o.kind !== 'keepout').forEach((o) => [0, 1, 2, 3, 4, 5, 6, 7].forEach((k) => {
    const p = [0, 1, 2].map((i) => ((k >> i) & 1 ? o.hi : o.lo)[i]); // each corner, where the block puts it
    grow(o.placed ? o.placed.r.map((row, i) => row[0] * p[0] + row[1] * p[1] + row[2] * p[2] + o.placed.t[i]) : p);
  }));
  s.places.forEach((p) => grow(p.at));
  centre = new THREE.Vector3((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2);
  span = Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) + 8;
  const tz = s.table === null ? 0 : s.table;
  const table = new THREE.Mesh(new THREE.PlaneGeometry(hi[0] - lo[0] + 12, hi[1] - lo[1] + 12),
                               new THREE.MeshBasicMaterial({ color: COLOURS.table, side: THREE.DoubleSide }));
  table.position.set(centre.x, centre.y, tz - 0.02);
  scene3.add(table);
  const grid = new THREE.GridHelper(Math.ceil(span / 6) * 6, Math.ceil(span / 6), 0xc0b8a0, 0xd4cdb8); // 6 in squares
  grid.rotation.x = Math.PI / 2;
  grid.position.set(Math.round(centre.x), Math.round(centre.y), tz);
  scene3.add(grid);
  scene3.add(new THREE.AxesHelper(4)); // x red, y green, z blue at the arm's base
  s.obstacles.forEach(obstacle);
  const seen = {};
  s.places.forEach((p) => {
    const rack = p.count > 1;
    const m = new THREE.Mesh(new THREE.SphereGeometry(rack ? 0.18 : 0.3, 12, 8),
                             new THREE.MeshBasicMaterial({ color: rack ? COLOURS.rack : COLOURS.place }));
    m.position.copy(v3(p.at));
    scene3.add(m);
    if (!seen[p.site]) { // one label per site: a rack's at its first position
      seen[p.site] = true;
      addLabel(rack ? p.site + ' (' + p.count + ')' : p.site, p.at, rack ? 'rack' : 'place');
    }
  });
  armGroup = new THREE.Group();
  scene3.add(armGroup);
  toolMark = new THREE.Mesh(new THREE.SphereGeometry(0.5, 16, 12),
                            new THREE.MeshBasicMaterial({ color: COLOURS.tool, depthTest: false }));
  toolMark.renderOrder = 10; // drawn over everything: the tool point is never hidden
  toolMark.visible = false;
  scene3.add(toolMark);
}

function segment(a, b, r, colour) {
  const d = new THREE.Vector3().subVectors(b, a);
  const len = d.length();
  if (len < 1e-6) return;
  const m = new THREE.Mesh(new THREE.CylinderGeometry(r, r, len, 16), new THREE.MeshBasicMaterial({ color: colour }));
  m.position.copy(a).addScaledVector(d, 0.5);
  m.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), d.normalize());
  armGroup.add(m);
  armGroup.add(edges(m, 0x7a5200));
}

function drawArm(chain) {
  armGroup.children.slice().forEach((c) => { armGroup.remove(c); if (c.geometry) c.geometry.dispose(); });
  const pts = [new THREE.Vector3(0, 0, 0)].concat(chain.map(v3));
  for (let i = 0; i + 1 < pts.length; i++) segment(pts[i], pts[i + 1], ARM_RADII[i], COLOURS.arm);
  pts.slice(1, 4).forEach((p) => {
    const j = new THREE.Mesh(new THREE.SphereGeometry(0.8, 16, 12), new THREE.MeshBasicMaterial({ color: COLOURS.joint }));
    j.position.copy(p);
    armGroup.add(j);
  });
  toolMark.position.copy(pts[4]);
  toolMark.visible = true;
}

function setView(which) {
  const d = span * 1.4;
  camera.up.set(0, 0, 1);
  if (which === 'top') camera.position.set(centre.x, centre.y - 0.001, centre.z + d); // x across, y up
  else if (which === 'side') camera.position.set(centre.x, centre.y - d, centre.z); // x across, z up
  else camera.position.set(centre.x + d * 0.75, centre.y - d * 0.55, centre.z + d * 0.55); // from the front right, above
  controls.target.copy(centre);
  controls.update();
}

function placeLabels() {
  const w = renderer.domElement.clientWidth, h = renderer.domElement.clientHeight;
  const taken = [];
  if (toolMark && toolMark.visible) { // no name ever covers the tool point
    const t = toolMark.position.clone().project(camera);
    const tx = (t.x + 1) / 2 * w, ty = (1 - t.y) / 2 * h;
    taken.push([tx - 12, ty - 12, tx + 12, ty + 12]);
  }
  const show = $('show-labels').checked;
  labels.forEach((l) => {
    const p = l.at.clone().project(camera);
    const visible = show && p.z < 1 && Math.abs(p.x) <= 1 && Math.abs(p.y) <= 1;
    l.div.style.display = visible ? '' : 'none';
    if (!visible) return;
    let x = (p.x + 1) / 2 * w, y = (1 - p.y) / 2 * h;
    const bw = l.div.offsetWidth || 60, bh = l.div.offsetHeight || 14;
    for (let k = 0; k < 4; k++) { // moved down a line while it would cover a label placed before
      const box = [x - bw / 2, y - bh * 1.2, x + bw / 2, y - bh * 0.2];
      if (!taken.some((t) => box[0] < t[2] && t[0] < box[2] && box[1] < t[3] && t[1] < box[3])) {
        taken.push(box);
        l.div.style.left = x + 'px';
        l.div.style.top = y + 'px';
        return;
      }
      y += bh;
    }
    l.div.style.display = 'none'; // no room: its object still shows its name on hover in the list
  });
}

function frame() {
  controls.update();
  renderer.render(scene3, camera);
  placeLabels();
  if (page.pendingDraw) { // the reading drawn now: the delay from the controller's answer to the picture
    page.delays.push(Date.now() - page.pendingDraw * 1000);
    page.pendingDraw = null;
  }
  requestAnimationFrame(frame);
}

function startView(s) {
  const view = $('view');
  renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio);
  view.insertBefore(renderer.domElement, view.firstChild);
  camera = new THREE.PerspectiveCamera(40, 1, 0.5, 2000);
  buildScene(s);
  controls = new THREE.OrbitControls(camera, renderer.domElement);
  controls.screenSpacePanning = true;
  const resize = () => {
    renderer.setSize(view.clientWidth, view.clientHeight);
    camera.aspect = view.clientWidth / view.clientHeight;
    camera.updateProjectionMatrix();
  };
  window.addEventListener('resize', resize);
  resize();
  setView('3d');
  ['3d', 'top', 'side'].forEach((v) => { $('v-' + v).onclick = () => setView(v); });
  requestAnimationFrame(frame);
}

// for the tests and for anyone at the console: the camera's matrices and the canvas on the page
page.camera = () => {
  camera.updateMatrixWorld();
  const r = renderer.domElement.getBoundingClientRect();
  return { projection: camera.projectionMatrix.elements.slice(), view: camera.matrixWorldInverse.elements.slice(),
           left: r.left, top: r.top, width: r.width, height: r.height };
};
page.setView = setView;

// ------------------------------------------------------------------ the arm's numbers
function fmt(v) { return v === undefined || v === null ? '-' : v.toFixed(3); }

function showPose(m) {
  lastPose = m;
  const w = m.world;
  if (w && w.length >= 6) {
    $('p-x').textContent = fmt(w[0]) + ' in'; $('p-y').textContent = fmt(w[1]) + ' in';
    $('p-z').textContent = fmt(w[2]) + ' in'; $('p-yaw').textContent = fmt(w[3]) + '°';
    $('p-pitch').textContent = fmt(w[4]) + '°'; $('p-roll').textContent = fmt(w[5]) + '°';
  }
  $('joints').textContent = 'joints ' + m.joints.map((j) => j.toFixed(2)).join(' ');
  if (m.chain) {
    drawArm(m.chain);
    page.pendingDraw = m.read_at;
    page.poses++;
  } else if (m.chain_error) {
    note('the arm cannot be drawn: ' + m.chain_error, true);
  }
  page.lastPose = m;
  showReading();
}

function showReading() {
  const el = $('reading');
  if (!lastPose) return;
  const age = Date.now() / 1000 - lastPose.read_at;
  const moving = armState !== 'Idle';
  const estimated = moving || age > ESTIMATED_AFTER_S;
  el.className = estimated ? 'estimated' : '';
  el.textContent = (estimated ? 'estimated: ' : '') + 'read ' + age.toFixed(1) + ' s ago' +
    (moving ? ' (the arm is ' + armState.toLowerCase() + ')' : '');
  page.estimated = estimated;
}
setInterval(showReading, 250);

// ------------------------------------------------------------------ methods and runs
function note(text, error) {
  const li = document.createElement('li');
  li.textContent = new Date().toLocaleTimeString() + ' ' + text;
  if (error) li.className = 'error';
  $('messages').prepend(li);
}

function showMethod() {
  const m = methods.find((x) => x.name === $('method').value);
  const form = $('params');
  form.innerHTML = '';
  $('method-text').textContent = m ? m.text : 'the method library is empty (--methods DIR)';
  if (!m) return;
  m.params.forEach((p) => {
    const label = document.createElement('label');
    label.textContent = p.name + ' ';
    const input = document.createElement('input');
    Object.assign(input, { type: 'number', name: p.name, min: p.min, max: p.max, step: 1, value: p.value,
                           required: true, title: p.text });
    label.appendChild(input);
    label.appendChild(document.createTextNode(' ' + p.unit + ' (' + p.min + '..' + p.max + ')'));
    form.appendChild(label);
  });
}

function send(req) {
  if (!ws || ws.readyState !== WebSocket.OPEN) { note('not connected to the station', true); return; }
  ws.send(JSON.stringify(req));
}

function runMethod() {
  const p = params();
  if (p) send({ op: 'run', method: $('method').value, params: p });
}

function dryRun() {
  const p = params();
  if (!p) return;
  $('plan').textContent = 'dry run of ' + $('method').value + ' ...';
  send({ op: 'dryrun', method: $('method').value, params: p });
}

function params() {
  const out = {};
  for (const input of $('params').querySelectorAll('input')) {
    const v = Number(input.value);
    if (!Number.isInteger(v) || v < Number(input.min) || v > Number(input.max)) {
      note(input.name + ' must be a whole number in ' + input.min + '..' + input.max, true);
      return null;
    }
    out[input.name] = v;
  }
  return out;
}

// the dry run's path, each motion coloured by the clearance the guard measured for it (the whole
// arm's, to the nearest obstacle): refused red, closer than CLOSE_IN orange, else green
const PATH_COLOURS = { refused: 0xff0000, close: 0xff9900, clear: 0x10b010 };
const CLOSE_IN = 0.5;
const PATH_R = 0.12; // in: the path's drawn thickness

function pathColour(seg) {
  if (!seg.sent) return PATH_COLOURS.refused;
  return seg.clearance !== null && seg.clearance < CLOSE_IN ? PATH_COLOURS.close : PATH_COLOURS.clear;
}

function drawSegment(seg, add) {
  const mat = new THREE.MeshBasicMaterial({ color: pathColour(seg), depthTest: false });
  for (let k = 1; k < seg.points.length; k++) { // a thin rod between each two points (WebGL lines are 1 px)
    const a = v3(seg.points[k - 1]), b = v3(seg.points[k]), len = a.distanceTo(b);
    if (len < 1e-6) continue;
    const rod = new THREE.Mesh(new THREE.CylinderGeometry(PATH_R, PATH_R, len, 8), mat);
    rod.position.copy(a.clone().add(b).multiplyScalar(0.5));
    rod.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), b.clone().sub(a).normalize());
    rod.renderOrder = seg.sent ? 5 : 6; // over the obstacles (a refused one goes into one), under the tool point
    add(rod);
  }
}

function legend(el) {
  const d = document.createElement('div');
  d.className = 'legend';
  [['refused', 'refused (nothing sent)'], ['close', 'clearance < ' + CLOSE_IN + ' in'], ['clear', 'clear']].forEach(([k, text]) => {
    const sw = document.createElement('span');
    sw.className = 'swatch';
    sw.style.background = '#' + PATH_COLOURS[k].toString(16).padStart(6, '0');
    d.appendChild(sw);
    d.appendChild(document.createTextNode(' ' + text + ' '));
  });
  el.appendChild(d);
}

let planMarks = []; // the path, the refused motions' points of contact (red), the closest approach (orange)
let planLabels = [];
function showPlan(r) {
  page.plan = r;
  const el = $('plan');
  el.innerHTML = '';
  const line = (text, cls) => { const d = document.createElement('div'); d.textContent = text; if (cls) d.className = cls; el.appendChild(d); };
  line('Dry run of ' + r.method + ': ' + (r.duration_s === null ? 'no duration' : 'predicted ' + r.duration_s.toFixed(1) + ' s') +
       (r.outcome ? ', ' + r.outcome : '') + (r.status ? ' (fbrlmon exit ' + r.status + ')' : ''));
  r.samples.forEach((x) => line('sample ' + x.sample + ': ' + x.outcome, x.outcome.startsWith('succeeded') ? '' : 'error'));
  r.refused.forEach((x) => line('refused: ' + x, 'refused'));
  r.errors.forEach((x) => line('error: ' + x, 'error'));
  planMarks.forEach((x) => scene3.remove(x));
  planMarks = [];
  planLabels.forEach((l) => l.div.remove());
  labels = labels.filter((l) => !planLabels.includes(l));
  planLabels = [];
  const segs = r.segments || [];
  segs.forEach((seg) => drawSegment(seg, (m) => { scene3.add(m); planMarks.push(m); }));
  segs.filter((seg) => !seg.sent && seg.points.length).forEach((seg) => {
    const what = seg.hit ? 'refused: ' + seg.word + ' would hit ' + seg.hit : 'refused: ' + seg.word;
    addLabel(what, seg.at || seg.points[seg.points.length - 1], 'refusal');
    planLabels.push(labels[labels.length - 1]);
  });
  if (segs.length) {
    legend(el);
    const close = segs.filter((seg) => seg.sent && seg.clearance !== null && seg.clearance < CLOSE_IN);
    line('path: ' + segs.length + ' motions checked, ' + segs.filter((seg) => !seg.sent).length + ' refused, ' +
         close.length + ' closer than ' + CLOSE_IN + ' in' + (close.length ? ' (' + close.slice(0, 5).map((seg) =>
           seg.word + ' ' + seg.clearance.toFixed(3) + ' in to ' + seg.near).join('; ') + (close.length > 5 ? '; ...' : '') + ')' : ''));
  }
  const mark = (at, colour, r) => {
    const m = new THREE.Mesh(new THREE.SphereGeometry(r, 12, 8), new THREE.MeshBasicMaterial({ color: colour }));
    m.position.copy(v3(at));
    scene3.add(m);
    planMarks.push(m);
  };
  r.refused.forEach((x) => { // the guard's message names the obstacle and the point of contact
    const hit = /would hit (\S+) with the (.+?) at X (\S+) Y (\S+) Z (\S+) in/.exec(x);
    if (hit) mark([Number(hit[3]), Number(hit[4]), Number(hit[5])], 0xff0000, 0.45);
  });
  if (r.closest) {
    line('smallest clearance ' + r.closest.clearance.toFixed(3) + ' in to ' + r.closest.obstacle + ' (' + r.closest.word + ')');
    mark(r.closest.at, 0xd07000, 0.3);
  }
  if (r.picture) { // the library's picture of the plan: the tool's path, the closest approach
    const img = document.createElement('img');
    img.src = URL.createObjectURL(new Blob([r.picture], { type: 'image/svg+xml' }));
    img.alt = 'the dry run (CELL-SVG)';
    img.onclick = () => window.open(img.src);
    el.appendChild(img);
  }
}

function showControl() {
  $('control').textContent = controlBy === null ? 'no one controls the runs'
    : controlBy === me ? 'you control the runs' : controlBy + ' controls the runs';
  const mine = controlBy === me;
  ['run', 'pause', 'resume', 'abort'].forEach((id) => { $(id).disabled = !mine; });
  $('take').disabled = controlBy !== null;
  $('release').disabled = !mine;
}

function stepRows(run) {
  const m = methods.find((x) => x.name === run.method);
  const t = $('steps');
  t.innerHTML = '';
  currentRun = { uuid: run.uuid, rows: {} };
  (m ? m.steps : []).forEach((s, i) => {
    const tr = t.insertRow();
    tr.insertCell().textContent = (i + 1) + ' ' + s.name;
    tr.insertCell().textContent = s.per_sample ? 'per sample' : '';
    tr.insertCell().textContent = '';
    currentRun.rows[i + 1] = tr;
  });
}

function onProgress(p) {
  const tr = currentRun && currentRun.rows[p.step];
  const where = p.step_name + (p.sample ? ', sample ' + p.sample + ' of ' + p.samples : '');
  if (tr) {
    if (p.event === 'StepStarted') { tr.className = 'going'; tr.cells[2].textContent = p.sample ? 'sample ' + p.sample + ' of ' + p.samples : 'going'; }
    if (p.event === 'StepEnded') { tr.className = 'done'; tr.cells[2].textContent = p.sample ? 'sample ' + p.sample + ' done' : 'done'; }
    if (p.event === 'StepFailed') { tr.className = 'failed'; tr.cells[2].textContent = 'failed'; }
  }
  note(p.event + ' ' + where + (p.message ? ': ' + p.message : ''), p.event === 'StepFailed');
}

function onQuestions(qs) {
  const q = $('question');
  q.innerHTML = '';
  qs.forEach((x) => {
    const d = document.createElement('div');
    d.textContent = x.error + ': ' + x.message;
    q.appendChild(d);
    [['Retry', 'run the step again'], ['SkipSample', 'give this sample up'], ['Abort', 'stop the run']].forEach(([o, t]) => {
      const b = document.createElement('button');
      b.textContent = o;
      b.title = t;
      b.dataset.option = o;
      b.disabled = controlBy !== me;
      b.onclick = () => send({ op: 'answer', option: o });
      q.appendChild(b);
    });
  });
}

function onMessage(m) {
  switch (m.t) {
    case 'hello':
      me = m.you; controlBy = m.control; showControl();
      if (m.user) { $('user').textContent = m.user.name + ' (' + m.user.role + ')'; $('signed-in').hidden = false; }
      $('audit').hidden = !m.lab;
      break;
    case 'control': controlBy = m.by; showControl(); note(m.by ? m.by + ' controls the runs' : 'no one controls the runs'); break;
    case 'pose': showPose(m); break;
    case 'state': armState = m.state; $('arm-state').textContent = m.state; showReading(); break;
    case 'questions': onQuestions(m.questions); break;
    case 'run':
      stepRows(m);
      $('run-title').textContent = [m.method].concat(m.values.map((v) => v[0] + '=' + v[1])).join(' ') + ', started by ' + m.by;
      $('outcome').textContent = '';
      page.run = { uuid: m.uuid, events: [], end: null };
      note(m.method + ' started by ' + m.by);
      break;
    case 'progress': onProgress(m); if (page.run) page.run.events.push(m); break;
    case 'end':
      $('outcome').textContent = m.outcome + ': ' + m.summary;
      if (page.run) page.run.end = m;
      note('run ended: ' + m.summary, m.outcome !== 'completed');
      setTimeout(showHistory, 500); // the station records it as the run's result is set
      break;
    case 'started': break;
    case 'signedout': location.href = '/login'; break; // --lab: idle or signed out
    case 'plan': showPlan(m); break;
    case 'error': note(m.message, true); page.errors.push(m.message); break;
    default: break;
  }
}

async function showHistory() { // the station's past runs, newest first; each opens its log
  const runs = await fetch('/api/history').then((r) => r.json());
  const ol = $('history');
  ol.innerHTML = '';
  runs.forEach((r) => {
    const li = document.createElement('li');
    const a = document.createElement('a');
    a.href = '/history/' + r.uuid;
    a.target = '_blank';
    a.textContent = new Date(r.start * 1000).toLocaleString() + ' ' + r.method + ': ' + r.outcome;
    li.appendChild(a);
    li.appendChild(document.createTextNode(' (' + r.by + ', version ' + (r.version ? r.version.slice(0, 12) : 'not known') + ')'));
    if (r.version) li.title = 'method version ' + r.version;
    li.dataset.uuid = r.uuid;
    ol.appendChild(li);
  });
  page.history = runs;
}

function connect() {
  ws = new WebSocket((location.protocol === 'https:' ? 'wss://' : 'ws://') + location.host + '/ws');
  ws.onmessage = (ev) => onMessage(JSON.parse(ev.data));
  ws.onopen = () => { page.connected = true; page.marks.open = page.marks.open || performance.now(); };
  ws.onclose = () => { page.connected = false; note('the station went away; trying again', true); setTimeout(connect, 1000); };
}

async function main() {
  const [s, ms] = await Promise.all([fetch('/api/scene').then((r) => r.json()), fetch('/api/methods').then((r) => r.json())]);
  page.scene = s;
  page.marks.fetched = performance.now();
  $('arm-model').textContent = s.arm;
  methods = ms;
  ms.forEach((m) => { const o = document.createElement('option'); o.value = o.textContent = m.name; $('method').appendChild(o); });
  $('method').onchange = showMethod;
  showMethod();
  startView(s);
  page.marks.view = performance.now();
  $('run').onclick = runMethod;
  $('dry').onclick = dryRun;
  $('pause').onclick = () => send({ op: 'pause' });
  $('resume').onclick = () => send({ op: 'resume' });
  $('abort').onclick = () => { if (window.confirm('Abort the run? The arm halts, the outputs go off, ON-ABORT runs.')) send({ op: 'abort' }); };
  $('take').onclick = () => send({ op: 'control' });
  $('release').onclick = () => send({ op: 'release' });
  showControl();
  showHistory();
  connect();
  const wait = () => { // interactive: the view drawn, the arm on it, the station's messages coming
    if (page.connected && page.poses > 0) { page.ready = true; page.readyAt = performance.now(); } else setTimeout(wait, 10);
  };
  wait();
}
main().catch((e) => { page.errors.push(String(e)); note('the page could not start: ' + e, true); });
