/*
 * animate_page.js: the script of a run's page (--animate FILE.html),
 * built into the runtime (runtime/front/embed.py) and written after the JSON
 * block #eomc-data that runtime/front/animate.c writes: the draw items, shapes,
 * links, traces, camera, output names and the frames, each frame
 * [t, outputs..., then per item its position (3) and, for bodies and
 * frames, its rotation matrix to the world (9, row-major)].
 *
 * Frames are shown as they are (the nearest frame to a time, never
 * interpolated).  #t=T in the URL opens paused at the frame nearest T.
 * After the first render the title becomes "eomc ready"; errors go to
 * <pre id="errors"> (the page's first script catches them).
 */
(function () {
  'use strict';
  var D = JSON.parse(document.getElementById('eomc-data').textContent);
  var F = D.frames, nout = D.outputs.length, nf = F.length;
  var PALETTE = [0xd62728, 0x1f77b4, 0x2ca02c, 0xff7f0e, 0x9467bd, 0x8c564b, 0xe377c2,
                 0x17becf, 0xbcbd22, 0x7f7f7f];
  var BODY_COLOUR = 0x8899aa;

  document.body.style.cssText = 'margin:0;overflow:hidden;background:#f7f7f7;' +
    'font:13px sans-serif';
  var errors = document.getElementById('errors');
  errors.style.cssText = 'position:absolute;bottom:44px;left:8px;color:#b00;margin:0;' +
    'pointer-events:none';

  /* where each item's pose starts in a frame */
  var at = [], off = 1 + nout;
  D.items.forEach(function (it) {
    at.push(off);
    off += it.kind === 'body' || it.kind === 'frame' ? 12 : 3;
  });

  var renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(window.innerWidth, window.innerHeight);
  renderer.setClearColor(0xf7f7f7);
  document.body.appendChild(renderer.domElement);
  renderer.domElement.style.display = 'block';

  var scene = new THREE.Scene();
  scene.add(new THREE.AmbientLight(0xffffff, 0.55));
  var C = D.camera, ext = D.extent;
  var camera = new THREE.PerspectiveCamera(C.fov, window.innerWidth / window.innerHeight,
                                           ext * 1e-3, ext * 1e3);
  camera.up.set(C.up[0], C.up[1], C.up[2]);
  camera.position.set(C.position[0], C.position[1], C.position[2]);
  var head = new THREE.DirectionalLight(0xffffff, 0.6); /* a light at the camera */
  camera.add(head);
  scene.add(camera);
  var controls = new THREE.OrbitControls(camera, renderer.domElement);
  controls.target.set(C.target[0], C.target[1], C.target[2]);
  camera.lookAt(controls.target);
  controls.update();

  /* a grid of cells 10^k or 5 * 10^k wide, its lines through the world's
   * origin, under the motion's centre: for a planar scene the plane z = 0,
   * 40 cells across; else the horizontal plane through the motion's lowest
   * point (z up), about 1.6 extents across, short of the default camera
   * (a line that reaches behind the camera may not be drawn at all) */
  var cell = Math.pow(10, Math.floor(Math.log(ext) / Math.LN10));
  if (ext < 5 * cell) cell /= 2;
  var cells = D.planar ? 40 : 2 * Math.ceil(0.8 * ext / cell);
  var grid = new THREE.GridHelper(cells * cell, cells, 0xdadada, 0xdadada);
  grid.rotation.x = Math.PI / 2;
  grid.position.set(Math.round(D.centre[0] / cell) * cell, Math.round(D.centre[1] / cell) * cell,
                    D.planar ? -ext * 1e-3 : D.low[2] - ext * 1e-3);
  scene.add(grid);

  var radius = 0.02 * ext;
  function colour(k) { return PALETTE[k % PALETTE.length]; }
  function lit(c) {
    return new THREE.MeshLambertMaterial({color: c, emissive: c, emissiveIntensity: 0.35});
  }

  function shapeMesh(s) {
    var c = new THREE.Color(s.rgba[0], s.rgba[1], s.rgba[2]);
    var mat = lit(c.getHex());
    if (s.rgba[3] < 1) { mat.transparent = true; mat.opacity = s.rgba[3]; }
    var z = s.size, o, geo;
    if (s.type === 0) geo = new THREE.BoxGeometry(2 * z[0], 2 * z[1], 2 * z[2]);
    else if (s.type === 1) geo = new THREE.SphereGeometry(z[0], 24, 16);
    else if (s.type === 4) { geo = new THREE.SphereGeometry(1, 24, 16); }
    else geo = new THREE.CylinderGeometry(z[0], z[0], 2 * z[1], 24);
    o = new THREE.Mesh(geo, mat);
    if (s.type === 4) o.scale.set(z[0], z[1], z[2]);
    if (s.type === 2 || s.type === 3) { /* along z, as MuJoCo's */
      o.rotation.x = Math.PI / 2;
      var grp = new THREE.Group();
      grp.add(o);
      if (s.type === 2) [-1, 1].forEach(function (e) {
        var cap = new THREE.Mesh(new THREE.SphereGeometry(z[0], 24, 12), mat);
        cap.position.z = e * z[1];
        grp.add(cap);
      });
      o = grp;
    }
    var outer = new THREE.Group();
    outer.add(o);
    outer.position.set(s.pos[0], s.pos[1], s.pos[2]);
    outer.quaternion.set(s.quat[1], s.quat[2], s.quat[3], s.quat[0]);
    return outer;
  }

  /* one object per item, placed by its pose at each frame */
  var objs = D.items.map(function (it, k) {
    var o = new THREE.Group();
    if (it.kind === 'particle') {
      o.add(new THREE.Mesh(new THREE.SphereGeometry(radius, 24, 16), lit(colour(k))));
    } else if (it.kind === 'point') {
      o.add(new THREE.Mesh(new THREE.SphereGeometry(radius * 0.4, 12, 8), lit(0x444444)));
    } else if (it.kind === 'body') {
      var shaped = false;
      D.shapes.forEach(function (s) {
        if (s.item === k) { o.add(shapeMesh(s)); shaped = true; }
      });
      if (!shaped && it.box) {
        var b = it.box, h = b.half, r = b.rot;
        var box = new THREE.Mesh(new THREE.BoxGeometry(2 * h[0], 2 * h[1], 2 * h[2]),
                                 lit(colour(k)));
        box.matrixAutoUpdate = false;
        box.matrix.set(r[0], r[1], r[2], b.centre[0], r[3], r[4], r[5], b.centre[1],
                       r[6], r[7], r[8], b.centre[2], 0, 0, 0, 1);
        o.add(box);
      }
      if (D.axes === 2) o.add(new THREE.AxesHelper(ext * 0.1)); /* frames: true */
    } else if (it.kind === 'frame' && D.axes) {
      o.add(new THREE.AxesHelper(ext * 0.15));
    }
    o.matrixAutoUpdate = false;
    scene.add(o);
    return o;
  });

  function place(j) {
    var f = F[j];
    D.items.forEach(function (it, k) {
      var a = at[k], o = objs[k];
      if (it.kind === 'body' || it.kind === 'frame')
        o.matrix.set(f[a + 3], f[a + 4], f[a + 5], f[a],
                     f[a + 6], f[a + 7], f[a + 8], f[a + 1],
                     f[a + 9], f[a + 10], f[a + 11], f[a + 2], 0, 0, 0, 1);
      else
        o.matrix.makeTranslation(f[a], f[a + 1], f[a + 2]);
      o.matrixWorldNeedsUpdate = true;
    });
  }

  /* links: segments between items' positions */
  var linkGeo = new THREE.BufferGeometry();
  var linkPos = new Float32Array(Math.max(1, D.links.length) * 6);
  linkGeo.setAttribute('position', new THREE.BufferAttribute(linkPos, 3));
  scene.add(new THREE.LineSegments(linkGeo, new THREE.LineBasicMaterial({color: 0x333333})));

  /* traces: each item's path up to the current frame */
  var traces = D.traces.map(function (k) {
    var pos = new Float32Array(nf * 3);
    F.forEach(function (f, j) {
      pos[3 * j] = f[at[k]]; pos[3 * j + 1] = f[at[k] + 1]; pos[3 * j + 2] = f[at[k] + 2];
    });
    var geo = new THREE.BufferGeometry();
    geo.setAttribute('position', new THREE.BufferAttribute(pos, 3));
    /* the item's colour, paler: the item itself stands out on its path */
    var c = new THREE.Color(colour(k)).lerp(new THREE.Color(0xffffff), 0.6);
    var line = new THREE.Line(geo, new THREE.LineBasicMaterial({color: c}));
    line.frustumCulled = false;
    scene.add(line);
    return geo;
  });

  function update(j) {
    place(j);
    var f = F[j];
    D.links.forEach(function (l, i) {
      for (var e = 0; e < 2; e++)
        for (var c = 0; c < 3; c++) linkPos[6 * i + 3 * e + c] = f[at[l[e]] + c];
    });
    linkGeo.attributes.position.needsUpdate = true;
    linkGeo.computeBoundingSphere();
    traces.forEach(function (geo) { geo.setDrawRange(0, j + 1); });
    var txt = 't = ' + f[0].toPrecision(6);
    for (var k = 0; k < nout; k++) txt += '\n' + D.outputs[k] + ' = ' + f[1 + k].toPrecision(6);
    readout.textContent = txt;
    slider.value = j;
  }

  /* the controls: a bar at the bottom; the readout at the top left */
  var bar = document.createElement('div');
  bar.style.cssText = 'position:absolute;left:0;right:0;bottom:0;height:36px;display:flex;' +
    'align-items:center;gap:8px;padding:0 8px;background:rgba(255,255,255,0.85)';
  var play = document.createElement('button');
  play.id = 'play';
  var speed = document.createElement('select');
  speed.id = 'speed';
  [0.1, 0.25, 0.5, 1, 2, 5, 10].forEach(function (s) {
    var o = document.createElement('option');
    o.value = s; o.textContent = s + 'x';
    if (s === 1) o.selected = true;
    speed.appendChild(o);
  });
  var slider = document.createElement('input');
  slider.id = 'time';
  slider.type = 'range'; slider.min = 0; slider.max = nf - 1; slider.step = 1;
  slider.style.flex = '1';
  bar.appendChild(play); bar.appendChild(speed); bar.appendChild(slider);
  document.body.appendChild(bar);
  var readout = document.createElement('pre');
  readout.id = 'readout';
  readout.style.cssText = 'position:absolute;top:6px;left:8px;margin:0;padding:2px 4px;' +
    'background:rgba(255,255,255,0.7);pointer-events:none';
  document.body.appendChild(readout);

  var t0 = F[0][0], t1 = F[nf - 1][0];
  function nearest(t) { /* the frame nearest t (times ascend) */
    var lo = 0, hi = nf - 1;
    while (hi - lo > 1) { var mid = (lo + hi) >> 1; if (F[mid][0] <= t) lo = mid; else hi = mid; }
    return Math.abs(F[hi][0] - t) < Math.abs(t - F[lo][0]) ? hi : lo;
  }
  var frame = 0, time = t0, playing = true, last = null;
  var m = /[#&]t=([-+0-9.eE]+)/.exec(window.location.hash);
  if (m) { playing = false; time = Math.min(t1, Math.max(t0, parseFloat(m[1]))); }
  frame = nearest(time);
  function label() { play.textContent = playing ? 'pause' : 'play'; }
  label();
  play.onclick = function () {
    playing = !playing;
    if (playing && frame === nf - 1) { frame = 0; time = t0; }
    last = null; label();
  };
  slider.oninput = function () {
    frame = parseInt(slider.value, 10); time = F[frame][0]; update(frame);
  };

  window.addEventListener('resize', function () {
    camera.aspect = window.innerWidth / window.innerHeight;
    camera.updateProjectionMatrix();
    renderer.setSize(window.innerWidth, window.innerHeight);
  });

  var ready = false;
  function draw(now) {
    if (playing && nf > 1) {
      if (last !== null) time += (now - last) / 1000 * parseFloat(speed.value);
      last = now;
      if (time >= t1) { time = t1; playing = false; label(); }
      frame = nearest(time);
    }
    update(frame);
    controls.update();
    renderer.render(scene, camera);
    if (!ready) { ready = true; document.title = 'eomc ready'; }
    window.requestAnimationFrame(draw);
  }
  update(frame);
  renderer.render(scene, camera);
  draw(0);
  last = null;
})();
