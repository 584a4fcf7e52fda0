//! Executed instructions per lighting-controller step, counted by the emulator.
//!
//! Run under qemu with `-icount shift=N,align=off,sleep=off` (as `scripts/cross.sh` does):
//! there every executed instruction advances the virtual clock by exactly 2^N ns, so a counter
//! of that clock counts instructions: SysTick, counting the core clock, on a Cortex-M;
//! `minstret`, which qemu reads from the virtual clock, on RISC-V. The ticks per instruction are
//! calibrated on a loop of two instructions per iteration (`cortex_m::asm::delay`'s `subs`,
//! `bne`; `addi`, `bnez` on RISC-V): the difference between two lengths of it is a known number
//! of instructions. A run without `-icount` fails that calibration (the loops' ticks are not
//! proportional). The counter is `src/counter.rs`, shared with
//! `src/bin/calibration_instructions.rs`.
//!
//! For each of the controller example's 144 steps (`src/bin/controller.rs`, the same site,
//! date and configuration), this counts `sky_core::controller::step` as a whole and its parts
//! called one by one as `step` calls them: the sun's position (the fast one, Grena 2012), the sky's constructor
//! (`daylight::Daylight::refracted` at the site's elevation: the diffuse tables and the direct beam's 47 spectral bins), the
//! day's Earth-Sun distance (`Daylight::on_day`: the day of the year and Spencer's series), the
//! global light (their sum), chromaticity and CCT (`cct_duv`) and the LED drive levels; the parts' results must equal
//! the whole step's bit for bit. It prints the minimum, median and maximum over the day of
//! each, in instructions (the bracket's own instructions subtracted). Then two calls the step
//! does not make, for a controller that wants them: the light on a south-facing window
//! (`Daylight::tilted` on a vertical plane: the vertical planes' table) and on a roof tilted
//! 30° to the south (the table and the daylight sky's quadratures).

#![no_std]
#![no_main]

use qemu_check::{entry, hprintln};
use sky_core::SkyError;
use sky_core::color::{self, Xyy};
use sky_core::controller::{
    Decomposition, Light, Settings, clear_atmosphere, example_luminaire, step,
};
use sky_core::daylight::{self, Daylight};
use sky_core::solar::{Site, SunAlgorithm, UtcTime, grena};

// `SITE`, `DATE`, `STEP_MINUTES`, `AOD`, `FULL_SCALE_LUX` and `PWM_BITS`, from build.rs.
include!(concat!(env!("OUT_DIR"), "/controller_config.rs"));

#[path = "../counter.rs"]
mod counter;

use counter::{instructions, measure};

const _: u8 = PWM_BITS; // the PWM levels are the controller example's, not counted here

/// Steps in the day.
const STEPS: usize = (24 * 60 / STEP_MINUTES) as usize;

/// Instructions per part of the step, over the day (the steps it was measured at).
struct Counts {
    name: &'static str,
    steps: [u32; STEPS],
    measured: usize,
}

impl Counts {
    fn push(&mut self, instructions: u32) {
        if let Some(slot) = self.steps.get_mut(self.measured) {
            *slot = instructions;
            self.measured += 1;
        }
    }
}

/// The planes are lit at every this many steps (every 2 hours: the tilted one takes thousands
/// of times the step's instructions on the soft-float cores, whose run would otherwise outlast
/// qemu's time limit).
const PLANE_EVERY: usize = 12;

/// The window's and the roof's normals (+y north, +x east): facing south, and tilted 30° from
/// the horizontal towards the south.
const WINDOW: sky_core::Vec3 = sky_core::Vec3::new(0.0, -1.0, 0.0);
const ROOF: sky_core::Vec3 = sky_core::Vec3::new(0.0, -0.5, 0.866_025_4);

/// Runs the day and fills `counts` (whole step, sun, sky, the day's sunlight, illuminance, CCT,
/// drive; window and roof every [`PLANE_EVERY`] steps); `Ok(false)` if a part's result differs from the whole
/// step's or a plane's light is not finite and non-negative.
fn run(counts: &mut [Counts; 9], per_instruction: f64, empty: u64) -> Result<bool, SkyError> {
    let (year, month, day) = DATE;
    let site = Site::new(SITE.0, SITE.1, SITE.2)?;
    let lamp = example_luminaire()?;
    let full_output: f32 = lamp.channels().iter().map(|c| c.full_output).sum();
    let settings = Settings {
        aerosol_optical_depth: AOD,
        ozone_du: sky_core::daylight::OZONE_DU,
        precipitable_water: sky_core::efficacy::DEFAULT_PRECIPITABLE_WATER,
        light: Light::Global,
        full_scale_lux: FULL_SCALE_LUX,
        sun: SunAlgorithm::Fast,
        decomposition: Decomposition::Erbs,
    };
    let mut same = true;
    for (index, minute) in (0..24 * 60).step_by(STEP_MINUTES as usize).enumerate() {
        let time = UtcTime::new(year, month, day, minute / 60, minute % 60, 0.0)?;
        let (t_step, whole) = measure(|| step(&time, &site, &settings, &lamp, None));
        let whole = whole?;
        let (t_sun, sun) = measure(|| grena::sun_position(&time, &site));
        let sun = sun?;
        let atmosphere = clear_atmosphere(&site, &settings);
        let (t_sky, sky) = measure(|| Daylight::refracted(&sun, &atmosphere));
        let sky = sky?;
        let (t_day, sky) = measure(|| sky.on_day(time.day_of_year()));
        let (t_lux, illuminance) = measure(|| sky.global());
        let (t_cct, (colour, cct)) = measure(|| {
            let colour = color::xyz_to_xyy(illuminance);
            (colour, daylight::cct_of(illuminance))
        });
        let (t_drive, drive) = measure(|| {
            lamp.drive(Xyy {
                luminance: full_output * illuminance.y / FULL_SCALE_LUX,
                ..colour
            })
        });
        same &= whole.sun == sun
            && whole.daylight == sky
            && whole.illuminance == illuminance
            && whole.cct == cct
            && whole.drive == drive;
        for (c, t) in counts
            .iter_mut()
            .zip([t_step, t_sun, t_sky, t_day, t_lux, t_cct, t_drive])
        {
            c.push(instructions(t, per_instruction, empty));
        }
        if index % PLANE_EVERY == 0 {
            for (c, normal) in counts[7..].iter_mut().zip([WINDOW, ROOF]) {
                let (t, light) = measure(|| sky.tilted(normal));
                same &= light.is_finite() && light.min_element() >= 0.0;
                c.push(instructions(t, per_instruction, empty));
            }
        }
    }
    Ok(same)
}

#[entry]
fn main() -> ! {
    let (per_instruction, empty) = counter::start("controller-instructions");
    let part = |name| Counts {
        name,
        steps: [0; STEPS],
        measured: 0,
    };
    let mut counts = [
        part("controller::step"),
        part("  sun position (Grena 2012)"),
        part("  daylight (Daylight::refracted)"),
        part("  Earth-Sun distance (Daylight::on_day)"),
        part("  global light (Daylight::global)"),
        part("  chromaticity and CCT (cct_duv)"),
        part("  LED drive (Luminaire::drive)"),
        part("window, vertical (Daylight::tilted) *"),
        part("roof, 30 deg (Daylight::tilted) *"),
    ];
    let same = match run(&mut counts, per_instruction, empty) {
        Ok(same) => same,
        Err(error) => {
            hprintln!(
                "controller-instructions: FAIL: {}",
                qemu_check::Message(error)
            );
            qemu_check::finish(false)
        }
    };
    hprintln!(
        "controller-instructions: {} steps of {} min; executed instructions (qemu -icount, {:.3} \
         counter ticks per instruction)",
        STEPS,
        STEP_MINUTES,
        per_instruction
    );
    hprintln!(
        "{:<40} {:>10} {:>10} {:>10}",
        "part",
        "min",
        "median",
        "max"
    );
    for c in &mut counts {
        let steps = &mut c.steps[..c.measured];
        steps.sort_unstable();
        let n = steps.len();
        if n == 0 {
            continue;
        }
        hprintln!(
            "{:<40} {:>10} {:>10} {:>10}",
            c.name,
            steps[0],
            (steps[(n - 1) / 2] + steps[n / 2]) / 2,
            steps[n - 1]
        );
    }
    hprintln!(
        "* not part of the step; every {} steps ({} of the day's)",
        PLANE_EVERY,
        STEPS.div_ceil(PLANE_EVERY)
    );
    if !same {
        hprintln!(
            "controller-instructions: FAIL: the parts differ from the whole step, or a plane's light is not finite and non-negative"
        );
    }
    qemu_check::finish(same)
}
