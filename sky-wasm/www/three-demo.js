// The three.js demo: SkyMesh for the background (the physical daylight sky by default, from noon
// to the night), the sky as an environment map (PMREM) or a light probe (SH) for the objects,
// the sun from sky-core's SPA for a time of day. Every input redraws once (the scene is static
// between inputs).
import * as THREE from "three";
import init, { SunPosition } from "./pkg/sky_wasm.js";
import { SkyMesh, fromSkyFrame, skyEnvironment, skyLightProbe } from "./pkg/three.js";

await init();

const $ = (id) => document.getElementById(id);
const PLACE = { latitude: 48.21, longitude: 16.37, elevation: 190 }; // Vienna
const UTC_OFFSET_MIN = 120; // CEST
const WEIGHTS = { "neural-preetham": "preetham", "neural-hosek": "hosek" };

const canvas = $("scene");
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.toneMapping = THREE.ACESFilmicToneMapping;
renderer.toneMappingExposure = 1;
const scene = new THREE.Scene();
const camera = new THREE.PerspectiveCamera(50, canvas.width / canvas.height, 0.1, 2000);
camera.position.set(0, 1.6, 7);
camera.lookAt(0, 0.9, 0); // towards -z, north

const sky = new SkyMesh({ model: "daylight" });
sky.scale.setScalar(1000);
scene.add(sky);

const ground = new THREE.Mesh(
  new THREE.CircleGeometry(900, 96),
  new THREE.MeshStandardMaterial({ color: 0x7a7a72, roughness: 0.95 }),
);
ground.rotation.x = -Math.PI / 2;
scene.add(ground);
const objects = {
  white: new THREE.Mesh(new THREE.SphereGeometry(1, 64, 32), new THREE.MeshStandardMaterial({ color: 0xffffff, roughness: 0.6 })),
  metal: new THREE.Mesh(new THREE.SphereGeometry(0.8, 64, 32), new THREE.MeshStandardMaterial({ color: 0xffffff, metalness: 1, roughness: 0.12 })),
  box: new THREE.Mesh(new THREE.BoxGeometry(1.2, 1.2, 1.2), new THREE.MeshStandardMaterial({ color: 0xc8c8c8, roughness: 0.4 })),
  knot: new THREE.Mesh(new THREE.TorusKnotGeometry(0.45, 0.15, 160, 24), new THREE.MeshStandardMaterial({ color: 0xd0d0d0, metalness: 0.3, roughness: 0.3 })),
};
objects.white.position.set(0, 1, 0);
objects.metal.position.set(-2.4, 0.8, -0.6);
objects.box.position.set(2.3, 0.6, -0.4);
objects.box.rotation.y = 0.5;
objects.knot.position.set(0.9, 0.62, 2.0);
for (const o of Object.values(objects)) scene.add(o);

const pmrem = new THREE.PMREMGenerator(renderer);
let environment = null;
let probe = null;
/** The sun's direction in three's world, for the last drawn frame. */
let sunDirection = new THREE.Vector3(0, 1, 0);
let frame = 0;

function sunAt(minutesLocal) {
  // Local times before 02:00 are on 20 June in UTC.
  const utc = minutesLocal - UTC_OFFSET_MIN;
  const [day, minutes] = utc < 0 ? [20, utc + 1440] : [21, utc];
  const p = SunPosition.at(2026, 6, day, Math.floor(minutes / 60), minutes % 60, 0, PLACE.latitude, PLACE.longitude, PLACE.elevation);
  return { zenith: p.zenith, azimuth: p.azimuth, elevation: p.elevationDeg, compass: p.compassAzimuthDeg };
}

function draw() {
  const minutes = Number($("time").value);
  $("time-value").textContent = `${String(Math.floor(minutes / 60)).padStart(2, "0")}:${String(minutes % 60).padStart(2, "0")}`;
  const turbidity = Number($("turbidity").value);
  $("turbidity-value").textContent = turbidity.toFixed(1);
  const aod = Number($("aod").value);
  $("aod-value").textContent = aod.toFixed(2);
  const model = $("model").value;
  const light = $("light").value;
  try {
    const sun = sunAt(minutes);
    $("sun-readout").textContent = `sun ${sun.elevation.toFixed(1)}° high, compass azimuth ${sun.compass.toFixed(1)}°`;
    document.body.dataset.sunElevationDeg = sun.elevation.toFixed(3);
    const below = sun.zenith > Math.PI / 2;
    if (below && model !== "daylight") throw new Error("the sun is below the horizon: pick a time between sunrise and sunset, or the daylight sky");
    if (below && light === "probe") throw new Error("the light probe is the Preetham sky's SH, which needs the sun above the horizon: use the environment map");
    const s = Math.sin(sun.zenith);
    sunDirection = fromSkyFrame(s * Math.cos(sun.azimuth), s * Math.sin(sun.azimuth), Math.cos(sun.zenith));
    sky.model = model.startsWith("neural") ? "neural" : model;
    sky.weights = WEIGHTS[model] ?? "preetham";
    sky.material.uniforms.sunPosition.value.copy(sunDirection);
    sky.material.uniforms.turbidity.value = turbidity;
    sky.material.uniforms.aod.value = aod;
    sky.update();
    const scale = sky.material.uniforms.luminanceScale.value;
    $("exposure-readout").textContent = `${scale.toExponential(3)} per cd/m²`;
    environment?.dispose();
    environment = null;
    if (probe) scene.remove(probe);
    probe = null;
    if (light === "environment") {
      environment = skyEnvironment(renderer, sky, pmrem);
      scene.environment = environment.texture;
    } else {
      scene.environment = null;
      probe = skyLightProbe(sunDirection, turbidity, scale);
      scene.add(probe);
    }
    renderer.render(scene, camera);
    $("error").textContent = sky.error ?? "";
  } catch (e) {
    $("error").textContent = e.message;
  }
  frame += 1;
  document.body.dataset.frame = String(frame);
}

/** Canvas pixel (x from the left, y from the top) of a point of the scene. */
function pixelOf(point) {
  const v = point.clone().project(camera);
  return [Math.round((v.x + 1) / 2 * canvas.width), Math.round((1 - v.y) / 2 * canvas.height)];
}

/** The pixel of the white sphere's surface facing both the sun and the camera (lit and seen). */
function sunSidePixel() {
  const c = objects.white.position;
  const toCamera = camera.position.clone().sub(c).normalize();
  const n = sunDirection.clone().add(toCamera).normalize();
  return pixelOf(c.clone().addScaledVector(n, 1));
}

/** For the tests: what the scene holds and where things are drawn. */
window.skyDemo = { renderer, scene, camera, sky, objects, pixelOf, sunSidePixel, draw };

for (const id of ["time", "model", "light", "turbidity", "aod"]) $(id).addEventListener("input", draw);
draw();
document.body.dataset.ready = "true";
