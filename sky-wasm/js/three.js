// sky-wasm for three.js: the skies of sky-core drawn by their generated GLSL shaders, for scenes
// that use three's `Sky` today.
//
// - `SkyMesh`: a Mesh subclass with the interface of three's `Sky` (a BackSide unit box drawn on
//   the far plane, `material.uniforms.sunPosition` and `.turbidity`, linear HDR output through
//   three's tone-mapping and colour-space chunks), plus the model and its parameters; the
//   daylight sky (`model: "daylight"`) takes the sun down to 18° below the horizon and
//   `material.uniforms.aod`, the aerosol optical depth.
// - `skyEnvironment`: the sky prefiltered by PMREMGenerator, an environment map for PBR.
// - `skyLightProbe`: a LightProbe from the spherical-harmonics sky (3 bands ->
//   SphericalHarmonics3, converted to three's frame).
//
// Axes: three's world is y up; the sky is placed with x east, y up, z south (so -z is north),
// sky-core's frame being x east, y north, z up. Units: the shaders give cd/m² (Preetham, neural,
// SH, daylight) or O'Neil's relative units (AOAS); `luminanceScale` (set by `ev100` or automatic
// exposure, which holds from the daylight sky's night to its noon) turns them into the numbers
// three's tone mapping expects (docs/gpu.md).
//
// Call sky-wasm's `init()` (or `initSync`) before building a SkyMesh.

import {
  BackSide,
  BoxGeometry,
  LightProbe,
  Mesh,
  PMREMGenerator,
  Scene,
  ShaderMaterial,
  SphericalHarmonics3,
  Vector3,
} from "three";
import { Sky, daylightDefaultAod } from "./sky_wasm.js";
import * as shaders from "./shaders.js";

/** The shader models, as sky-wasm's `Sky.model` names them. */
export const MODELS = ["preetham", "neural", "aoas", "sh", "daylight"];

/** The error for a model SkyMesh cannot draw, the same from the constructor and from `update`. */
function checkModel(model) {
  if (!MODELS.includes(model)) throw new Error(`model = "${model}" is not one of ${MODELS.join(", ")}`);
}

/** sky-core's frame (x east, y north, z up) of a three.js world direction (y up, -z north). */
export function toSkyFrame(v) {
  return { x: v.x, y: -v.z, z: v.y };
}

/** The three.js world direction of a direction in sky-core's frame. */
export function fromSkyFrame(x, y, z) {
  return new Vector3(x, z, -y);
}

/** The sun's zenith angle and azimuth (radians, sky-core's convention: azimuth from east
 * towards north) of a three.js direction towards the sun (any length). */
export function sunAngles(sunPosition) {
  const s = toSkyFrame(sunPosition);
  const len = Math.hypot(s.x, s.y, s.z);
  return { zenith: Math.acos(Math.min(1, Math.max(-1, s.z / len))), azimuth: Math.atan2(s.y, s.x) };
}

/** The luminance scale of a camera exposure EV100: 1 / (1.2 · 2^EV100), the saturation-based
 * exposure of Lagarde and de Rousiers, "Moving Frostbite to Physically Based Rendering"
 * (SIGGRAPH 2014), §4.3.2. A sunny day is EV100 ≈ 15 ("sunny 16"). */
export function exposureOfEv100(ev100) {
  return 1 / (1.2 * 2 ** ev100);
}

const VERTEX = /* glsl */ `
varying vec3 vWorldPosition;
void main() {
  vec4 worldPosition = modelMatrix * vec4(position, 1.0);
  vWorldPosition = worldPosition.xyz;
  gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
  gl_Position.z = gl_Position.w; // on the far plane, as three's Sky
}
`;

function fragmentShader(model) {
  return `${shaders[model].glsl}
uniform float luminanceScale;
varying vec3 vWorldPosition;
void main() {
  vec3 w = normalize(vWorldPosition - cameraPosition);
  // three's world (x east, y up, z south) -> sky-core's frame (x east, y north, z up).
  vec3 radiance = sky_radiance(vec3(w.x, -w.z, w.y));
  // A channel outside the sRGB gamut (the daylight sky's deep-twilight blue) is clipped at 0,
  // as sky-wasm's 8-bit images clip it.
  gl_FragColor = vec4(max(radiance, 0.0) * luminanceScale, 1.0);
  #include <tonemapping_fragment>
  #include <colorspace_fragment>
}
`;
}

/**
 * The sky of one of sky-core's models as a three.js mesh, a drop-in for three's `Sky`:
 *
 * ```js
 * await init();                                   // sky-wasm
 * const sky = new SkyMesh({ model: "neural" });
 * sky.scale.setScalar(450000);
 * scene.add(sky);
 * sky.material.uniforms.sunPosition.value.copy(sun);
 * sky.material.uniforms.turbidity.value = 3;
 * renderer.toneMapping = THREE.ACESFilmicToneMapping;
 * ```
 *
 * The parameters are read before each render (`onBeforeRender`); sky-core rebuilds the sky on
 * the CPU when one has changed (microseconds) and its shader parameters go to the uniform
 * `sky_<model>`. A parameter sky-core rejects (a sun below the horizon for Preetham, a
 * turbidity out of range) leaves the last valid sky in place and its message in `error`.
 *
 * The daylight sky (`new SkyMesh({ model: "daylight" })`) is sky-core's physical clear sky
 * from noon to astronomical night: the sun anywhere (below 18° under the horizon it draws the
 * −18° sky) and `material.uniforms.aod.value`, the aerosol optical depth at 550 nm (sky-wasm's
 * `daylightMinAod()` to `daylightMaxAod()`); a new sun or optical depth is a new uniform array,
 * never a new shader.
 */
export class SkyMesh extends Mesh {
  /**
   * @param {object} [options]
   * @param {"preetham"|"neural"|"aoas"|"sh"|"daylight"} [options.model] the sky model (default
   *   preetham)
   * @param {number} [options.turbidity] turbidity (Preetham 2-6, SH 2.5-6, neural: the trained
   *   range; not used by AOAS and daylight), default 3
   * @param {number} [options.aod] the daylight sky's aerosol optical depth at 550 nm (default
   *   sky-wasm's `daylightDefaultAod()`)
   * @param {"preetham"|"hosek"|Uint8Array} [options.weights] the neural sky's weights: a shipped
   *   set or a weight file's bytes (default "preetham")
   * @param {string} [options.preset] the AOAS style preset without patterns (default "physical")
   * @param {number} [options.bands] SH bands, 1 to 7 (default 3)
   * @param {number|null} [options.ev100] camera exposure; null (default) for automatic exposure
   *   (the sky's mean luminance to middle grey)
   */
  constructor({ model = "preetham", turbidity = 3, aod = daylightDefaultAod(), weights = "preetham", preset = "physical", bands = 3, ev100 = null } = {}) {
    checkModel(model);
    const uniforms = {
      sunPosition: { value: new Vector3(0, 1, 0) },
      turbidity: { value: turbidity },
      aod: { value: aod },
      luminanceScale: { value: 1 },
    };
    for (const m of MODELS) uniforms[`sky_${m}`] = { value: new Float32Array(4 * shaders[m].params) };
    const material = new ShaderMaterial({
      name: "SkyWasmShader",
      uniforms,
      vertexShader: VERTEX,
      fragmentShader: fragmentShader(model),
      side: BackSide,
      depthWrite: false,
    });
    super(new BoxGeometry(1, 1, 1), material);
    this.isSky = true;
    /** The sky model. */
    this.model = model;
    /** The neural sky's weights. */
    this.weights = weights;
    /** The AOAS style preset. */
    this.preset = preset;
    /** SH bands. */
    this.bands = bands;
    /** Camera exposure EV100, or null for automatic exposure. */
    this.ev100 = ev100;
    /** sky-core's message for the parameters last rejected, or null. */
    this.error = null;
    this._key = null;
    this._shaderModel = model;
    this.update();
  }

  /** A sky-wasm `Sky` for the current parameters (the caller frees it). Throws sky-core's
   * message for parameters out of range. */
  buildSky() {
    checkModel(this.model);
    const u = this.material.uniforms;
    const { zenith, azimuth } = sunAngles(u.sunPosition.value);
    const t = u.turbidity.value;
    switch (this.model) {
      case "preetham":
        return Sky.preetham(zenith, azimuth, t);
      case "neural":
        return typeof this.weights === "string"
          ? Sky.neural(this.weights, zenith, azimuth, t)
          : Sky.neuralFromBytes(this.weights, zenith, azimuth, t);
      case "aoas":
        return Sky.aoasWithSun(this.preset, zenith, azimuth);
      case "sh":
        return Sky.sh(zenith, azimuth, t, this.bands);
      case "daylight":
        return Sky.daylight(zenith, azimuth, u.aod.value);
    }
  }

  /** Rebuilds the sky if a parameter changed; throws sky-core's message (keeping the last
   * valid sky) for parameters out of range. Called before each render. */
  update() {
    const u = this.material.uniforms;
    const s = u.sunPosition.value;
    const key = [this.model, s.x, s.y, s.z, u.turbidity.value, u.aod.value, this.weights, this.preset, this.bands, this.ev100].join();
    if (key === this._key) return;
    const sky = this.buildSky();
    try {
      u[`sky_${this.model}`].value.set(sky.shaderParams());
      u.luminanceScale.value = this.ev100 === null ? sky.autoExposure() : exposureOfEv100(this.ev100);
    } finally {
      sky.free();
    }
    if (this._shaderModel !== this.model) {
      this.material.fragmentShader = fragmentShader(this.model);
      this.material.needsUpdate = true;
      this._shaderModel = this.model;
    }
    this._key = key;
  }

  onBeforeRender() {
    try {
      this.update();
      this.error = null;
    } catch (e) {
      this.error = e.message;
    }
  }
}

/**
 * An environment map of `skyMesh` for PBR materials (`scene.environment`): the sky rendered
 * into a cube map and prefiltered by PMREMGenerator, as three's own sky example does. Call it
 * again when the sky changes; dispose of the previous render target.
 *
 * @returns {import("three").WebGLRenderTarget}
 */
export function skyEnvironment(renderer, skyMesh, pmrem = new PMREMGenerator(renderer)) {
  skyMesh.update();
  const scene = new Scene();
  scene.add(new Mesh(skyMesh.geometry, skyMesh.material));
  return pmrem.fromScene(scene);
}

/** √3 / 2: band 2's mixing under the change of frame. */
const HALF_SQRT3 = Math.sqrt(3) / 2;

/**
 * A LightProbe lit by the spherical-harmonics sky of seed 001 (the Preetham sky's SH tables)
 * for a sun (a three.js direction) and turbidity (2.5 to 6): sky-core's 3-band radiance
 * coefficients without the ringing filter (the irradiance needs none), in three's frame.
 * sky-core's real SH and three's `SphericalHarmonics3` share the basis (orthonormal, no
 * Condon-Shortley phase, index l² + l + m); the change of axes (x, y, z)_sky = (x, -z, y)_three
 * maps band 1 by a permutation with a sign and mixes band 2's (2, 0) and (2, 2) terms.
 * `intensity` is the luminance scale (a SkyMesh's `material.uniforms.luminanceScale.value`).
 */
export function skyLightProbe(sunPosition, turbidity = 3, intensity = 1) {
  const { zenith, azimuth } = sunAngles(sunPosition);
  const sky = Sky.shUnfiltered(zenith, azimuth, turbidity, 3);
  let p;
  try {
    p = sky.shaderParams();
  } finally {
    sky.free();
  }
  const c = (i) => new Vector3(p[4 * i], p[4 * i + 1], p[4 * i + 2]);
  const mix = (a, b, ka, kb) => c(a).multiplyScalar(ka).addScaledVector(c(b), kb);
  const sh = new SphericalHarmonics3();
  sh.set([
    c(0),
    c(2), // y_three = z_sky
    c(1).negate(), // z_three = -y_sky
    c(3),
    c(7), // x y_three = x z_sky
    c(5).negate(), // y z_three = -(y z)_sky
    mix(6, 8, -0.5, -HALF_SQRT3),
    c(4).negate(), // x z_three = -(x y)_sky
    mix(6, 8, -HALF_SQRT3, 0.5),
  ]);
  return new LightProbe(sh, intensity);
}
