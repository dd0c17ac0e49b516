// dynrad's walk-through: the lit model of a .glb (embedded in the page as base64), shown
// as the solver left it (unlit materials, the light baked into the vertex colours), with
// first-person navigation, the file's viewpoints, an exposure control, false colour of
// luminance and a read-out of the values under the cross-hair.
//
// Runs on three.js r111 (Debian's libjs-three, inlined before this script) and its
// GLTFLoader. The page's state is kept on <body> for tests and scripts:
//   data-state   "loading", "ready" (the first frame is drawn) or "error"
//   data-errors  the number of errors reported (script errors, console.error)
//   data-view    the viewpoint shown last
//   data-camera  x,y,z,heading,pitch of the camera after the last frame drawn
//   data-mode    "colour" or "false"; data-ev the exposure's offset in stops
// The URL's hash may choose how the page opens: #view=NAME&mode=false&ev=-1&top=200, or
// #camera=x,y,z,heading,pitch for a place; the page keeps its hash up to date with the
// latter form whenever the view comes to rest, so the address can be bookmarked or sent.
(function () {
  'use strict';

  const config = JSON.parse(document.getElementById('dynrad-config').textContent);
  const body = document.body;
  const canvas = document.getElementById('view');
  const readout = document.getElementById('readout');
  const message = document.getElementById('message');

  function fail(text) {
    body.dataset.state = 'error';
    message.textContent = text;
    message.hidden = false;
  }

  // --- The model: base64 to bytes, bytes to three.js objects ---------------------------
  function modelBytes() {
    const text = document.getElementById('dynrad-model').textContent.replace(/\s+/g, '');
    const binary = atob(text);
    const bytes = new Uint8Array(binary.length);
    for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
    return bytes.buffer;
  }

  const renderer = new THREE.WebGLRenderer({canvas: canvas, antialias: true});
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0x202020);
  const camera = new THREE.PerspectiveCamera(60, 4 / 3, 0.01, 1000);
  camera.rotation.order = 'YXZ';  // yaw about the vertical, then pitch

  // Colour attributes are shared by every primitive (one buffer holds each vertex once),
  // so each is kept once here with its linear values and the values read out with it.
  const layers = [];  // {colour, linear, luminance, radiosity}
  let meshes = [];
  let litMeshes = [];  // those with the light in their vertex colours (not the glass)
  let viewpoints = [];  // {name, position, quaternion, fov}
  let bounds = new THREE.Box3();
  let background = null;  // [r, g, b] linear, from the scene's extras

  function collectLayers(root) {
    const seen = new Set();
    root.traverse(function (object) {
      if (!object.isMesh) return;
      meshes.push(object);
      const attributes = object.geometry.attributes;
      if (!attributes.color || seen.has(attributes.color)) return;
      seen.add(attributes.color);
      // Attributes may be interleaved (files from elsewhere), so values go through
      // getX/setXYZ rather than the arrays.
      const colour = attributes.color;
      const linear = new Float32Array(3 * colour.count);
      for (let i = 0; i < colour.count; ++i) {
        linear[3 * i] = colour.getX(i);
        linear[3 * i + 1] = colour.getY(i);
        linear[3 * i + 2] = colour.getZ(i);
      }
      layers.push({
        colour: colour,
        linear: linear,
        luminance: attributes._luminance || null,
        radiosity: attributes._radiosity || null,
        // False colour: the luminance's place on the scale as a texture coordinate into
        // the scale, so that the value (not the colour) is interpolated across each
        // triangle, as the report's pictures map each pixel.
        scale: new THREE.BufferAttribute(new Float32Array(2 * colour.count), 2),
      });
    });
    for (const mesh of meshes) {
      const geometry = mesh.geometry;
      const layer = layers.find(function (l) { return l.colour === geometry.attributes.color; });
      mesh.userData.dynrad = {
        trueMaterial: mesh.material,
        falseMaterial: new THREE.MeshBasicMaterial({map: scaleTexture(), side: mesh.material.side}),
        ownUv: geometry.attributes.uv || null,
        scaleUv: layer ? layer.scale : null,
      };
      if (layer) litMeshes.push(mesh);
    }
  }

  let texture = null;
  function scaleTexture() {
    if (texture) return texture;
    const n = 256, data = new Uint8Array(3 * n), c = [0, 0, 0];
    for (let k = 0; k < n; ++k) {
      falseColour(k / (n - 1), c);
      for (let j = 0; j < 3; ++j) data[3 * k + j] = Math.round(255 * c[j]);
    }
    texture = new THREE.DataTexture(data, n, 1, THREE.RGBFormat);
    texture.magFilter = texture.minFilter = THREE.LinearFilter;
    texture.needsUpdate = true;
    return texture;
  }

  // --- Colour: exposure and sRGB, or false colour ------------------------------------
  const state = {mode: 'colour', ev: 0, top: 1, view: ''};

  function srgb(c) {
    c = Math.max(0, c);
    return c <= 0.0031308 ? 12.92 * c : Math.min(1, 1.055 * Math.pow(c, 1 / 2.4) - 0.055);
  }

  // The same stops as the report's false-colour pictures (plugin/report/grid_picture.cpp).
  function falseColour(t, out) {
    const stops = config.palette;
    t = Math.min(1, Math.max(0, t)) * (stops.length - 1);
    const k = Math.min(stops.length - 2, Math.floor(t));
    const f = t - k;
    for (let c = 0; c < 3; ++c) out[c] = stops[k][c] * (1 - f) + stops[k + 1][c] * f;
    return out;
  }

  // The luminance-weighted sum of an RGB attribute's vertex i (Rec. 709 weights, as the
  // solver's).
  function rec709(attribute, i) {
    return 0.2126 * attribute.getX(i) + 0.7152 * attribute.getY(i) + 0.0722 * attribute.getZ(i);
  }

  // Luminance of vertex i of a layer: the file's _LUMINANCE (cd/m^2), else B / pi from
  // its _RADIOSITY.
  function luminanceAt(layer, i) {
    if (layer.luminance) return layer.luminance.getX(i);
    if (layer.radiosity) return rec709(layer.radiosity, i) / Math.PI;
    return NaN;
  }

  function paint() {
    const gain = Math.pow(2, state.ev);
    const rgb = [0, 0, 0];
    const falseMode = state.mode === 'false';
    for (const layer of layers) {
      if (falseMode) {
        // Texel centres of the 256-texel scale: 0.5 / 256 at 0, 255.5 / 256 at the top.
        for (let i = 0; i < layer.colour.count; ++i) {
          const l = luminanceAt(layer, i);
          const t = isNaN(l) ? 0 : Math.min(1, Math.max(0, l / state.top));
          layer.scale.setXY(i, (0.5 + 255 * t) / 256, 0.5);
        }
        layer.scale.needsUpdate = true;
        continue;
      }
      const colour = layer.colour, linear = layer.linear;
      for (let i = 0; i < colour.count; ++i) {
        rgb[0] = srgb(gain * linear[3 * i]);
        rgb[1] = srgb(gain * linear[3 * i + 1]);
        rgb[2] = srgb(gain * linear[3 * i + 2]);
        colour.setXYZ(i, rgb[0], rgb[1], rgb[2]);
      }
      if (colour.isInterleavedBufferAttribute) colour.data.needsUpdate = true;
      else colour.needsUpdate = true;
    }
    // The background: the file's (the sky of a daylight solve, linear like the vertex
    // colours) through the same exposure, else dark grey.
    if (background) scene.background.setRGB(srgb(gain * background[0]), srgb(gain * background[1]),
                                             srgb(gain * background[2]));
    for (const mesh of meshes) {
      const own = mesh.userData.dynrad;
      if (!own.scaleUv) continue;  // no colours: left as the file has it
      mesh.material = falseMode ? own.falseMaterial : own.trueMaterial;
      if (falseMode) mesh.geometry.setAttribute('uv', own.scaleUv);
      else if (own.ownUv) mesh.geometry.setAttribute('uv', own.ownUv);
      else mesh.geometry.deleteAttribute('uv');
    }
    document.getElementById('legend').hidden = state.mode !== 'false';
    document.getElementById('mode').textContent = state.mode === 'false' ? 'True colour (F)' : 'False colour (F)';
    document.getElementById('ev-value').textContent = (state.ev > 0 ? '+' : '') + state.ev.toFixed(1) + ' EV';
    drawLegend();
    requestDraw();
  }

  function drawLegend() {
    const bar = document.getElementById('legend-bar');
    const stops = config.palette.map(function (c, k) {
      return 'rgb(' + c.map(function (v) { return Math.round(255 * v); }).join(',') + ') ' +
             (100 * (1 - k / (config.palette.length - 1))).toFixed(1) + '%';
    });
    bar.style.background = 'linear-gradient(to bottom, ' + stops.reverse().join(', ') + ')';
    const ticks = document.getElementById('legend-ticks');
    ticks.textContent = '';
    const step = niceStep(state.top);
    for (let v = 0; v <= state.top * (1 + 1e-9); v += step) {
      const tick = document.createElement('div');
      tick.style.top = (100 * (1 - v / state.top)) + '%';
      tick.textContent = formatValue(v) + (v >= state.top * (1 - 1e-9) ? '+' : '');
      ticks.appendChild(tick);
    }
    document.getElementById('legend-unit').textContent = 'Luminance, ' + config.luminance_unit;
    document.getElementById('top').value = state.top;
  }

  // The legend's top, as the report's pictures choose it (plugin/report/grid_picture.cpp's
  // legend_scale): the least of 1, 2, 2.5, 5 and 10 times a power of ten at or above the
  // 98th percentile of the vertices' luminance.
  function automaticTop() {
    const values = [];
    for (const layer of layers) {
      for (let i = 0; i < layer.colour.count; ++i) {
        const l = luminanceAt(layer, i);
        if (l > 0) values.push(l);
      }
    }
    if (!values.length) return 1;
    values.sort(function (x, y) { return x - y; });
    const peak = values[Math.min(values.length - 1, Math.floor(0.98 * values.length))];
    const power = Math.pow(10, Math.floor(Math.log10(peak)));
    for (const m of [1, 2, 2.5, 5, 10])
      if (m * power >= peak * (1 - 1e-12)) return m * power;
    return 10 * power;
  }

  function niceStep(top) {
    const power = Math.pow(10, Math.floor(Math.log10(top) + 1e-9));
    const m = top / power;
    const near = function (x) { return Math.abs(m - x) < 1e-6; };
    return top / (near(2.5) ? 5 : near(1) || near(10) ? 10 : near(2) ? 8 : 5);
  }

  function formatValue(v) {
    if (v === 0) return '0';
    if (Math.abs(v) >= 100) return v.toFixed(0);
    if (Math.abs(v) >= 10) return v.toFixed(1);
    return v.toPrecision(2);
  }

  // --- Navigation: walk and look -----------------------------------------------------
  const keys = new Set();
  let speed = 1;       // model units per second, from the model's size
  let drawPending = false, readoutDone = false;
  // Movement follows the time the keys are held, not the frames drawn: each step goes
  // from the last one to now, and releasing a key takes the last step, so a slow
  // machine walks as far, in fewer frames.
  let moveClock = 0;

  function requestDraw() {
    if (drawPending) return;
    drawPending = true;
    requestAnimationFrame(frame);
  }

  function advance() {
    const now = performance.now();
    if (keys.size && moveClock) move(Math.min(2, (now - moveClock) / 1000));  // no leap after a stall
    moveClock = now;
  }

  function frame() {
    drawPending = false;
    if (keys.size) advance();
    resize();
    renderer.render(scene, camera);
    body.dataset.mode = state.mode;
    body.dataset.ev = String(state.ev);
    if (body.dataset.state === 'loading') body.dataset.state = 'ready';
    if (!keys.size && !readoutDone) scheduleReadout();
  }

  function move(dt) {
    const fast = keys.has('Shift') ? 4 : 1;
    const step = speed * fast * dt;
    const forward = new THREE.Vector3(-Math.sin(camera.rotation.y), 0, -Math.cos(camera.rotation.y));
    const right = new THREE.Vector3(-forward.z, 0, forward.x);
    const d = new THREE.Vector3();
    if (keys.has('w') || keys.has('ArrowUp')) d.add(forward);
    if (keys.has('s') || keys.has('ArrowDown')) d.sub(forward);
    if (keys.has('d') || keys.has('ArrowRight')) d.add(right);
    if (keys.has('a') || keys.has('ArrowLeft')) d.sub(right);
    if (keys.has('e') || keys.has('PageUp')) d.y += 1;
    if (keys.has('q') || keys.has('PageDown')) d.y -= 1;
    if (d.lengthSq() > 0) camera.position.addScaledVector(d.normalize(), step);
    cameraMoved();
  }

  // Called whenever the camera changes: the page's state on <body> says where it is.
  function cameraMoved() {
    body.dataset.camera = cameraText();
    readoutDone = false;
    requestDraw();
  }

  function resize() {
    const w = canvas.clientWidth, h = canvas.clientHeight;
    if (canvas.width !== Math.floor(w * renderer.getPixelRatio()) ||
        canvas.height !== Math.floor(h * renderer.getPixelRatio())) {
      renderer.setSize(w, h, false);
      camera.aspect = w / Math.max(1, h);
      camera.updateProjectionMatrix();
    }
  }

  const movementKeys = ['w', 'a', 's', 'd', 'q', 'e', 'ArrowUp', 'ArrowDown', 'ArrowLeft', 'ArrowRight',
                        'PageUp', 'PageDown', 'Shift'];
  window.addEventListener('keydown', function (event) {
    if (event.target.tagName === 'INPUT' || event.target.tagName === 'SELECT') return;
    const key = event.key.length === 1 ? event.key.toLowerCase() : event.key;
    if (movementKeys.indexOf(key) >= 0) {
      advance();
      keys.add(key);
      event.preventDefault();
      requestDraw();
    } else if (key === 'f') {
      setMode(state.mode === 'false' ? 'colour' : 'false');
    } else if (key === 'Home') {
      showViewpoint(viewpoints.length ? viewpoints[0].name : '');
    } else if (key >= '1' && key <= '9' && viewpoints[Number(key) - 1]) {
      showViewpoint(viewpoints[Number(key) - 1].name);
    } else if (key === '+' || key === '=') {
      setExposure(state.ev + 0.5);
    } else if (key === '-') {
      setExposure(state.ev - 0.5);
    }
  });
  window.addEventListener('keyup', function (event) {
    advance();
    keys.delete(event.key.length === 1 ? event.key.toLowerCase() : event.key);
    if (event.key === 'Shift') keys.delete('Shift');
  });
  window.addEventListener('blur', function () { advance(); keys.clear(); });

  // Dragging looks around; the wheel walks forward and back.
  let drag = null;
  canvas.addEventListener('pointerdown', function (event) {
    drag = {x: event.clientX, y: event.clientY};
    canvas.setPointerCapture(event.pointerId);
  });
  canvas.addEventListener('pointermove', function (event) {
    if (!drag) return;
    const scale = camera.fov * Math.PI / 180 / Math.max(1, canvas.clientHeight);
    camera.rotation.y += (event.clientX - drag.x) * scale;
    camera.rotation.x = Math.max(-1.55, Math.min(1.55, camera.rotation.x + (event.clientY - drag.y) * scale));
    drag = {x: event.clientX, y: event.clientY};
    cameraMoved();
  });
  canvas.addEventListener('pointerup', function () { drag = null; });
  canvas.addEventListener('wheel', function (event) {
    event.preventDefault();
    const forward = new THREE.Vector3();
    camera.getWorldDirection(forward);
    camera.position.addScaledVector(forward, -Math.sign(event.deltaY) * speed * 0.25);
    cameraMoved();
  }, {passive: false});
  window.addEventListener('resize', requestDraw);

  // --- Read-out: the values under the cross-hair, once the view is still ----------------
  const raycaster = new THREE.Raycaster();
  let readoutTimer = 0;

  function scheduleReadout() {
    clearTimeout(readoutTimer);
    readoutTimer = setTimeout(updateReadout, 150);
  }

  // Where the camera is: x, y, z (the file's axes, y up), then its heading and pitch in
  // degrees; the form #camera= takes.
  function cameraText() {
    const p = camera.position;
    return [p.x, p.y, p.z].map(function (v) { return v.toFixed(3); }).join(',') + ',' +
           [camera.rotation.y, camera.rotation.x].map(function (v) { return (v * 180 / Math.PI).toFixed(2); }).join(',');
  }

  // The address of what is shown, so that it can be bookmarked or sent: the page's own
  // URL with #camera=...&mode=...&ev=...&top=...
  function updateAddress() {
    const parts = ['camera=' + cameraText()];
    if (state.mode === 'false') parts.push('mode=false', 'top=' + state.top);
    if (state.ev !== 0) parts.push('ev=' + state.ev);
    try {
      history.replaceState(null, '', '#' + parts.join('&'));
    } catch (error) {
      // Some browsers refuse this for local files; the page works without it.
    }
  }

  function updateReadout() {
    readoutDone = true;
    updateAddress();
    raycaster.setFromCamera(new THREE.Vector2(0, 0), camera);
    raycaster.near = camera.near;
    // The read-out looks through glass, at the lit surfaces.
    const hit = raycaster.intersectObjects(litMeshes, false)[0];
    if (!hit || !hit.face) {
      readout.textContent = 'Cross-hair: nothing';
      return;
    }
    const geometry = hit.object.geometry;
    const a = hit.face.a, b = hit.face.b, c = hit.face.c;
    const p = geometry.attributes.position;
    const corner = function (i) { return new THREE.Vector3().fromBufferAttribute(p, i).applyMatrix4(hit.object.matrixWorld); };
    const weights = new THREE.Vector3();
    THREE.Triangle.getBarycoord(hit.point, corner(a), corner(b), corner(c), weights);
    const attributes = geometry.attributes;
    const value = function (attribute) {
      if (!attribute) return NaN;
      const at = function (i) { return attribute.itemSize === 1 ? attribute.getX(i) : rec709(attribute, i); };
      return weights.x * at(a) + weights.y * at(b) + weights.z * at(c);
    };
    const parts = ['Distance ' + hit.distance.toFixed(2) + ' ' + config.length_unit];
    const luminance = attributes._luminance ? value(attributes._luminance) : value(attributes._radiosity) / Math.PI;
    if (!isNaN(luminance)) parts.push('luminance ' + formatValue(luminance) + ' ' + config.luminance_unit);
    if (attributes._illuminance) parts.push('illuminance ' + formatValue(value(attributes._illuminance)) + ' lx');
    else if (attributes._radiosity) parts.push('radiosity ' + formatValue(value(attributes._radiosity)) + ' W/m\u00b2');
    parts.push('(' + hit.object.name + ')');
    readout.textContent = parts.join(', ');
  }

  // --- Viewpoints --------------------------------------------------------------------
  function showViewpoint(name) {
    const v = viewpoints.find(function (p) { return p.name === name; });
    if (v) {
      camera.position.copy(v.position);
      const direction = new THREE.Vector3(0, 0, -1).applyQuaternion(v.quaternion);
      camera.rotation.set(Math.asin(Math.max(-1, Math.min(1, direction.y))), Math.atan2(-direction.x, -direction.z), 0);
      camera.fov = v.fov;
    } else {
      // No viewpoint in the file: from outside, looking at the middle.
      const centre = bounds.getCenter(new THREE.Vector3());
      const size = bounds.getSize(new THREE.Vector3()).length();
      camera.position.copy(centre).add(new THREE.Vector3(0.6, 0.4, 0.9).multiplyScalar(size));
      const d = centre.clone().sub(camera.position).normalize();
      camera.rotation.set(Math.asin(d.y), Math.atan2(-d.x, -d.z), 0);
      camera.fov = 50;
    }
    camera.updateProjectionMatrix();
    state.view = v ? v.name : '';
    body.dataset.view = state.view;
    document.getElementById('views').value = state.view;
    cameraMoved();
  }

  function setMode(mode) {
    state.mode = mode;
    paint();
  }

  function setExposure(ev) {
    state.ev = Math.max(-8, Math.min(8, ev));
    document.getElementById('ev').value = state.ev;
    paint();
  }

  function hashOptions() {
    const options = {};
    window.location.hash.replace(/^#/, '').split('&').forEach(function (pair) {
      const at = pair.indexOf('=');
      if (at > 0) options[decodeURIComponent(pair.slice(0, at))] = decodeURIComponent(pair.slice(at + 1));
    });
    return options;
  }

  function start(gltf) {
    const root = gltf.scene;
    const extras = root.userData || {};
    if (Array.isArray(extras.background) && extras.background.length === 3 && extras.background.every(isFinite))
      background = extras.background.map(Number);
    scene.add(root);
    root.updateMatrixWorld(true);
    collectLayers(root);
    if (!meshes.length) throw new Error('the file holds no meshes');
    meshes.forEach(function (m) { bounds.expandByObject(m); });
    const size = bounds.getSize(new THREE.Vector3()).length();
    speed = Math.min(1.4, size / 8);  // at most a walking pace in a building
    camera.near = Math.max(1e-4, size / 5000);
    camera.far = size * 20;
    root.traverse(function (object) {
      if (!object.isCamera) return;
      viewpoints.push({
        name: object.name || ('view' + (viewpoints.length + 1)),
        position: object.getWorldPosition(new THREE.Vector3()),
        quaternion: object.getWorldQuaternion(new THREE.Quaternion()),
        fov: object.fov || 60,
      });
    });
    const select = document.getElementById('views');
    viewpoints.forEach(function (v, k) {
      const option = document.createElement('option');
      option.value = v.name;
      option.textContent = (k < 9 ? (k + 1) + ': ' : '') + v.name;
      select.appendChild(option);
    });
    if (!viewpoints.length) select.hidden = true;
    select.addEventListener('change', function () { showViewpoint(select.value); canvas.focus(); });
    document.getElementById('mode').addEventListener('click', function () {
      setMode(state.mode === 'false' ? 'colour' : 'false');
    });
    document.getElementById('ev').addEventListener('input', function (event) { setExposure(Number(event.target.value)); });
    document.getElementById('top').addEventListener('change', function (event) {
      const top = Number(event.target.value);
      if (top > 0 && isFinite(top)) state.top = top;
      paint();
    });

    state.top = config.top > 0 ? config.top : automaticTop();
    const options = hashOptions();
    if (options.top !== undefined && Number(options.top) > 0) state.top = Number(options.top);
    if (options.ev !== undefined && isFinite(Number(options.ev))) state.ev = Number(options.ev);
    document.getElementById('ev').value = state.ev;
    if (options.mode === 'false') state.mode = 'false';
    showViewpoint(options.view !== undefined ? options.view : (viewpoints.length ? viewpoints[0].name : ''));
    const place = (options.camera || '').split(',').map(Number);
    if (place.length === 5 && place.every(isFinite)) {
      camera.position.set(place[0], place[1], place[2]);
      camera.rotation.set(place[4] * Math.PI / 180, place[3] * Math.PI / 180, 0);
      cameraMoved();
      state.view = '';
      body.dataset.view = '';
      document.getElementById('views').value = '';
    }
    paint();
  }

  body.dataset.state = 'loading';
  try {
    new THREE.GLTFLoader().parse(modelBytes(), '', function (gltf) {
      try {
        start(gltf);
      } catch (error) {
        console.error(error);
        fail('The model could not be shown: ' + error.message);
      }
    }, function (error) {
      console.error(error);
      fail('The model could not be read: ' + (error && error.message ? error.message : error));
    });
  } catch (error) {
    console.error(error);
    fail('The model could not be read: ' + error.message);
  }
})();
