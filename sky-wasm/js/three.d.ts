// Types of three.js (sky-wasm's three.js drop-in).
import { LightProbe, Mesh, PMREMGenerator, ShaderMaterial, Vector3, WebGLRenderer, WebGLRenderTarget } from "three";
import { Sky } from "./sky_wasm.js";

/** The shader models, as sky-wasm's `Sky.model` names them. */
export const MODELS: readonly ["preetham", "neural", "aoas", "sh", "daylight"];
export type SkyModel = (typeof MODELS)[number];

/** sky-core's frame (x east, y north, z up) of a three.js world direction (y up, -z north). */
export function toSkyFrame(v: { x: number; y: number; z: number }): { x: number; y: number; z: number };
/** The three.js world direction of a direction in sky-core's frame. */
export function fromSkyFrame(x: number, y: number, z: number): Vector3;
/** The sun's zenith angle and azimuth (radians, sky-core's convention) of a three.js direction. */
export function sunAngles(sunPosition: Vector3): { zenith: number; azimuth: number };
/** 1 / (1.2 · 2^EV100): the luminance scale of a camera exposure. */
export function exposureOfEv100(ev100: number): number;

export interface SkyMeshOptions {
  model?: SkyModel;
  turbidity?: number;
  /** The daylight sky's aerosol optical depth at 550 nm (`material.uniforms.aod`). */
  aod?: number;
  weights?: "preetham" | "hosek" | Uint8Array;
  preset?: string;
  bands?: number;
  ev100?: number | null;
}

/** The sky of one of sky-core's models as a three.js mesh, a drop-in for three's `Sky`. */
export class SkyMesh extends Mesh<any, ShaderMaterial> {
  constructor(options?: SkyMeshOptions);
  readonly isSky: true;
  model: SkyModel;
  weights: "preetham" | "hosek" | Uint8Array;
  preset: string;
  bands: number;
  ev100: number | null;
  /** sky-core's message for the parameters last rejected, or null. */
  error: string | null;
  /** A sky-wasm Sky for the current parameters (the caller frees it). */
  buildSky(): Sky;
  /** Rebuilds the sky if a parameter changed; throws for parameters out of range. */
  update(): void;
}

/** An environment map of the sky (PMREMGenerator), for `scene.environment`. */
export function skyEnvironment(renderer: WebGLRenderer, skyMesh: SkyMesh, pmrem?: PMREMGenerator): WebGLRenderTarget;
/** A LightProbe lit by the 3-band SH sky for a sun and turbidity (2.5 to 6). */
export function skyLightProbe(sunPosition: Vector3, turbidity?: number, intensity?: number): LightProbe;
