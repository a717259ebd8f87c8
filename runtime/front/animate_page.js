/*
 * animate_page.js: the script of a run's page (--animate FILE.html),
 * built into the runtime (runtime/front/embed.py) and written after the JSON
 * block #eomc-data that runtime/front/animate.c writes: the draw items, shapes,
 * links, traces, camera, output names and the frames, each frame
 * [t, outputs..., then per item its position (3) and, for bodies and
 * frames, its rotation matrix to the world (9, row-major)].
 *
 * Frames are shown as they are (the nearest frame to a time, never
 * interpolated).  #t=T in the URL opens paused at the frame nearest T;
 * #follow=NAME has the camera follow that item (#follow=none: not the
 * view's).  After the first render the title becomes "eomc ready"; errors
 * go to <pre id="errors"> (the page's first script catches them).
 * Without WebGL the page says so in its text, and its title is
 * "eomc: no WebGL".
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

  /* the page draws with WebGL: without it, it says so where it is read */
  var renderer = null;
  try {
    renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
  } catch (e) { renderer = null; }
  if (!renderer) {
    var no = document.createElement('div');
    no.id = 'nowebgl';
    no.style.cssText = 'margin:2em;max-width:40em;font:15px sans-serif;line-height:1.4';
    no.textContent = 'This page draws the motion of \'' + D.name + '\' with WebGL, and this ' +
      'browser gives it no WebGL: it is turned off, or no graphics driver supports it. ' +
      'Open the page in a browser with WebGL on. A headless Chromium has WebGL in ' +
      'software with --enable-unsafe-swiftshader.';
    document.body.insertBefore(no, errors);
    errors.style.position = 'static';
    document.title = 'eomc: no WebGL';
    return;
  }
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
   * origin, under the motion's centre (or the item the camera follows):
   * for a planar scene the plane z = 0, 40 cells across; else the model's
   * ground, the plane across the camera's up (its axis nearest it: z
   * unless the view says otherwise) at the height D.floor (0 unless the
   * view says otherwise), about 1.6 extents across, short of the default
   * camera (a line that reaches behind the camera may not be drawn at
   * all).  A hair below the plane, not to hide what lies on it. */
  var cell = Math.pow(10, Math.floor(Math.log(ext) / Math.LN10));
  if (ext < 5 * cell) cell /= 2;
  var cells = D.planar ? 40 : 2 * Math.ceil(0.8 * ext / cell);
  var grid = new THREE.GridHelper(cells * cell, cells, 0xdadada, 0xdadada);
  var upAxis = 2;
  if (!D.planar)
    [0, 1].forEach(function (i) {
      if (Math.abs(C.up[i]) > Math.abs(C.up[upAxis])) upAxis = i;
    });
  var upSign = D.planar || C.up[upAxis] >= 0 ? 1 : -1;
  if (upAxis === 2) grid.rotation.x = Math.PI / 2; /* GridHelper lies across y */
  else if (upAxis === 0) grid.rotation.z = Math.PI / 2;
  function placeGrid(c) { /* under c, by whole cells */
    var p = [0, 1, 2].map(function (i) { return Math.round(c[i] / cell) * cell; });
    p[upAxis] = (D.planar ? 0 : D.floor) - upSign * ext * 1e-3;
    grid.position.set(p[0], p[1], p[2]);
  }
  placeGrid(D.centre);
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

  /* a body without shapes: the uniform solid of its mass and inertia, in
   * its principal axes; a cylinder (along the axes' z) with a darker spoke
   * along their x, so that its turn about its axis shows */
  function solidMesh(b, c) {
    var h = b.half, r = b.rot, grp = new THREE.Group();
    if (b.type === 'cylinder') {
      var cyl = new THREE.Mesh(new THREE.CylinderGeometry(h[0], h[0], 2 * h[2], 48), lit(c));
      cyl.rotation.x = Math.PI / 2;
      grp.add(cyl);
      var dark = new THREE.Color(c).lerp(new THREE.Color(0x000000), 0.45).getHex();
      var spoke = new THREE.Mesh(new THREE.BoxGeometry(h[0], 0.12 * h[0],
                                                       2 * h[2] + 0.04 * h[0]), lit(dark));
      spoke.position.x = h[0] / 2;
      grp.add(spoke);
    } else {
      grp.add(new THREE.Mesh(new THREE.BoxGeometry(2 * h[0], 2 * h[1], 2 * h[2]), lit(c)));
    }
    grp.matrixAutoUpdate = false;
    grp.matrix.set(r[0], r[1], r[2], b.centre[0], r[3], r[4], r[5], b.centre[1],
                   r[6], r[7], r[8], b.centre[2], 0, 0, 0, 1);
    return grp;
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
      if (!shaped && it.solid) o.add(solidMesh(it.solid, colour(k)));
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

  /* the camera following item fk: it moves as the item moves (the mouse
   * still orbits and zooms about it).  Started by the view's `follow:`
   * with the view's camera as given, else aimed at the item from where the
   * camera looks, at the distance that frames everything drawn about the
   * item over the motion: at least a tenth of the motion's extent, so
   * that a lone particle is not blown up to fill the view. */
  var FOLLOW_LEAST = 0.1;
  var fk = -1, fpos = null;
  function posOf(k, j) { var a = at[k]; return [F[j][a], F[j][a + 1], F[j][a + 2]]; }
  function reachOf(it) { return it.reach + (it.kind === 'particle' ? radius : 0); }
  function follow(k, j, aim) {
    fk = k;
    if (k < 0) return;
    fpos = posOf(k, j);
    if (!aim) return;
    var far = FOLLOW_LEAST * ext;
    F.forEach(function (f, jj) {
      var c = posOf(k, jj);
      D.items.forEach(function (it, i) {
        var a = at[i], d = Math.hypot(f[a] - c[0], f[a + 1] - c[1], f[a + 2] - c[2]);
        if (isFinite(d)) far = Math.max(far, d + reachOf(it));
      });
    });
    var dir = camera.position.clone().sub(controls.target).normalize();
    var dist = far / Math.sin(C.fov * Math.PI / 360);
    controls.target.set(fpos[0], fpos[1], fpos[2]);
    camera.position.copy(controls.target).addScaledVector(dir, dist);
    camera.lookAt(controls.target);
  }
  function followTo(j) {
    if (fk < 0) return;
    var p = posOf(fk, j);
    if (!p.every(isFinite)) return;
    var d = new THREE.Vector3(p[0] - fpos[0], p[1] - fpos[1], p[2] - fpos[2]);
    camera.position.add(d);
    controls.target.add(d);
    fpos = p;
    placeGrid([controls.target.x, controls.target.y, controls.target.z]);
  }

  function update(j) {
    place(j);
    followTo(j);
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
  var follows = document.createElement('select');
  follows.id = 'follow';
  follows.title = 'the item the camera follows';
  [{name: 'fixed camera', k: -1}].concat(D.items.map(function (it, k) {
    return {name: 'follow ' + it.name, k: k};
  })).forEach(function (e) {
    var o = document.createElement('option');
    o.value = e.k; o.textContent = e.name;
    follows.appendChild(o);
  });
  bar.appendChild(play); bar.appendChild(speed); bar.appendChild(follows);
  bar.appendChild(slider);
  document.body.appendChild(bar);
  var readout = document.createElement('pre');
  readout.id = 'readout';
  readout.style.cssText = 'position:absolute;top:6px;left:8px;margin:0;padding:2px 4px;' +
    'background:rgba(255,255,255,0.7);pointer-events:none';
  document.body.appendChild(readout);
  /* what is not drawn as the model has it */
  var notes = document.createElement('div');
  notes.id = 'notes';
  notes.style.cssText = 'position:absolute;top:6px;right:8px;max-width:45%;text-align:right;' +
    'color:#963;background:rgba(255,255,255,0.7);pointer-events:none';
  D.items.forEach(function (it) {
    if (it.unturned)
      notes.textContent += 'body \'' + it.name + '\' is drawn unturned: the model gives ' +
        'its angular velocity, not its orientation. ';
  });
  document.body.appendChild(notes);

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
  var want = /[#&]follow=([^&]*)/.exec(window.location.hash), fstart = D.follow;
  if (want) {
    fstart = -1;
    D.items.forEach(function (it, k) {
      if (it.name === decodeURIComponent(want[1])) fstart = k;
    });
  }
  /* the view's own camera, following the view's item, starts as given */
  follow(fstart, 0, !(C.given && fstart === D.follow)); /* the view's camera is at t0's */
  follows.value = fk;
  follows.onchange = function () { follow(parseInt(follows.value, 10), frame, true); };
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
