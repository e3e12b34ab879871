// The replay page: the embedded glTF (the shot) in three.js, with orbit controls,
// play / pause, a time slider, speed, the events to jump to and a top view.
// The URL's hash can set the start: #t=1.5&view=top (or camera=NAME)&clean, which the
// tests use to take screenshots; window.shot offers the same to scripts.
(function () {
  'use strict';
  const T = THREE;
  const text = document.getElementById('shot').textContent.trim();
  const bytes = Uint8Array.from(atob(text), (c) => c.charCodeAt(0));
  const options = new URLSearchParams(location.hash.slice(1));
  if (options.has('clean')) document.body.classList.add('clean');

  const view = document.getElementById('view');
  const renderer = new T.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.outputColorSpace = T.SRGBColorSpace;
  renderer.toneMapping = T.ACESFilmicToneMapping;
  view.appendChild(renderer.domElement);
  const scene = new T.Scene();
  scene.background = new T.Color(0x15171a);
  scene.add(new T.HemisphereLight(0xfff6e8, 0x202018, 1.2));
  const lamp = new T.DirectionalLight(0xffffff, 1.6);
  lamp.position.set(0.3, 4, 0.6);
  scene.add(lamp);

  let camera = new T.PerspectiveCamera(40, 1, 0.01, 100);
  const controls = new T.OrbitControls(camera, renderer.domElement);
  let top = null;   // the orthographic top camera, and its half extents
  let fixed = null; // a camera of the film chosen by #camera=NAME
  let mixer = null;
  let duration = 0;
  let time = 0;
  let playing = false;
  let speed = 1;
  let last = null;
  let dirty = true; // draw only when something changed: an idle page costs nothing
  const slider = document.getElementById('time');
  const clock = document.getElementById('clock');
  const playButton = document.getElementById('play');
  const topButton = document.getElementById('top');
  const list = document.getElementById('events');
  let events = [];

  function size() {
    const width = view.clientWidth, height = view.clientHeight;
    renderer.setSize(width, height, false);
    const aspect = width / Math.max(height, 1);
    camera.aspect = aspect;
    camera.updateProjectionMatrix();
    if (top) {
      // The table fills the view: widen whichever side the window's shape leaves over.
      const [hx, hy] = top.half;
      const sx = Math.max(hx, hy * aspect), sy = sx / aspect;
      top.camera.left = -sx; top.camera.right = sx; top.camera.top = sy; top.camera.bottom = -sy;
      top.camera.updateProjectionMatrix();
    }
    if (fixed) { fixed.aspect = aspect; fixed.updateProjectionMatrix(); }
    dirty = true;
  }

  function setTime(t) {
    time = Math.min(Math.max(t, 0), duration);
    if (mixer) mixer.setTime(time);
    slider.value = String(time);
    clock.textContent = time.toFixed(3) + ' s';
    dirty = true;
    list.querySelectorAll('li').forEach((item, k) => item.classList.toggle('past', events[k].t <= time));
  }

  function setPlaying(on) {
    playing = on;
    if (on && time >= duration) setTime(0);
    playButton.textContent = on ? 'Pause' : 'Play';
    playButton.setAttribute('aria-pressed', String(on));
    last = null;
  }

  function setTop(on) {
    topButton.setAttribute('aria-pressed', String(on));
    controls.enabled = !on && !fixed;
    dirty = true;
  }

  function active() {
    if (topButton.getAttribute('aria-pressed') === 'true' && top) return top.camera;
    return fixed || camera;
  }

  function frame(now) {
    if (playing && last !== null) {
      setTime(time + ((now - last) / 1000) * speed);
      if (time >= duration) setPlaying(false);
    }
    if (playing) last = now;
    controls.update();
    if (dirty || playing) renderer.render(scene, active());
    dirty = false;
    requestAnimationFrame(frame);
  }

  function describe(event) {
    const balls = event.balls.join(' & ');
    if (event.kind === 'pocket') return `${balls} drops (${event.pocket})`;
    if (event.kind === 'ball') return `${balls} touch`;
    return `${balls} ${event.pocket ? 'jaw' : 'cushion'}`;
  }

  new T.GLTFLoader().parse(bytes.buffer, '', (gltf) => {
    scene.add(gltf.scene);
    const clip = gltf.animations[0];
    duration = clip.duration;
    mixer = new T.AnimationMixer(gltf.scene);
    const action = mixer.clipAction(clip);
    action.setLoop(T.LoopOnce, 1);
    action.clampWhenFinished = true;
    action.play();
    slider.max = String(duration);
    events = (gltf.parser.json.animations[0].extras || {}).events || [];
    events.forEach((event) => {
      const item = document.createElement('li');
      item.innerHTML = `<span>${event.t.toFixed(3)}</span>`;
      item.append(describe(event));
      item.addEventListener('click', () => { setPlaying(false); setTime(event.t); });
      list.appendChild(item);
    });
    // Cameras: the film's first shot starts the orbit view; the top one is kept apart.
    gltf.cameras.forEach((cam) => {
      const data = cam.userData || {};
      if (cam.isOrthographicCamera) top = { camera: cam, half: data.half_extent };
      else if (data.camera === options.get('camera')) fixed = cam;
    });
    // The orbit view starts wide, from beyond the head rail's corner, at the table's centre.
    const [length, width] = (gltf.scene.userData || {}).table_size || [2.54, 1.27];
    camera.position.set(-0.85 * length, 0.75 * length, 0.9 * width);
    controls.target.set(0, 0, 0);
    controls.update();
    setTop(options.get('view') === 'top');
    size();
    setTime(parseFloat(options.get('t') || '0') || 0);
    document.body.dataset.ready = 'true';
  }, (error) => { document.body.textContent = 'This page could not read its shot: ' + error; });

  playButton.addEventListener('click', () => setPlaying(!playing));
  slider.addEventListener('input', () => { setPlaying(false); setTime(parseFloat(slider.value)); });
  document.getElementById('speed').addEventListener('change', (e) => { speed = parseFloat(e.target.value); });
  topButton.addEventListener('click', () => setTop(topButton.getAttribute('aria-pressed') !== 'true'));
  window.addEventListener('keydown', (e) => {
    if (e.key === ' ') { e.preventDefault(); setPlaying(!playing); }
    if (e.key === 't') setTop(topButton.getAttribute('aria-pressed') !== 'true');
  });
  window.addEventListener('resize', size);
  controls.addEventListener('change', () => { dirty = true; });
  window.shot = {
    get duration() { return duration; },
    get time() { return time; },
    setTime, setPlaying, setTop,
  };
  requestAnimationFrame(frame);
})();
