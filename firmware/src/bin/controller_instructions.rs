//! Executed instructions per lighting-controller step, counted by the emulator.
//!
//! Run under qemu with `-icount shift=N,align=off,sleep=off` (as `scripts/cross.sh` does):
//! there every executed instruction advances the virtual clock by exactly 2^N ns, so a counter
//! of that clock counts instructions: SysTick, counting the core clock, on a Cortex-M;
//! `minstret`, which qemu reads from the virtual clock, on RISC-V. The ticks per instruction are
//! calibrated on a loop of two instructions per iteration (`cortex_m::asm::delay`'s `subs`,
//! `bne`; `addi`, `bnez` on RISC-V): the difference between two lengths of it is a known number
//! of instructions. A run without `-icount` fails that calibration (the loops' ticks are not
//! proportional).
//!
//! For each of the controller example's 144 steps (`src/bin/controller.rs`, the same site,
//! date and configuration), this counts `sky_core::controller::step` as a whole and its parts
//! called one by one as `step` calls them: the sun's position (the fast one, Grena 2012), the sky's constructor
//! (`daylight::Daylight::new`: the diffuse tables and the direct beam's 47 spectral bins), the
//! global light (their sum), chromaticity and CCT (`cct_duv`) and the LED drive levels; the parts' results must equal
//! the whole step's bit for bit. It prints the minimum, median and maximum over the day of
//! each, in instructions (the bracket's own instructions subtracted). Then two calls the step
//! does not make, for a controller that wants them: the light on a south-facing window
//! (`Daylight::tilted` on a vertical plane: the vertical planes' table) and on a roof tilted
//! 30° to the south (the table and the daylight sky's quadratures).

#![no_std]
#![no_main]

use core::hint::black_box;

use qemu_check::{entry, hprintln};
use sky_core::SkyError;
use sky_core::color::{self, Xyy};
use sky_core::controller::{Decomposition, Light, Settings, example_luminaire, step};
use sky_core::daylight::{self, Daylight};
use sky_core::solar::{Site, SunAlgorithm, UtcTime, grena};

// `SITE`, `DATE`, `STEP_MINUTES`, `AOD`, `FULL_SCALE_LUX` and `PWM_BITS`, from build.rs.
include!(concat!(env!("OUT_DIR"), "/controller_config.rs"));

const _: u8 = PWM_BITS; // the PWM levels are the controller example's, not counted here

/// Steps in the day.
const STEPS: usize = (24 * 60 / STEP_MINUTES) as usize;
/// Iterations of the calibration loop (two instructions each).
const CALIBRATION: u32 = 200_000;

/// The counter on a Cortex-M: SysTick, counting the core clock down from its 24-bit reload.
#[cfg(target_arch = "arm")]
mod counter {
    use core::sync::atomic::{AtomicU32, Ordering};

    use cortex_m::peripheral::syst::SystClkSource;
    use cortex_m::peripheral::{SCB, SYST};
    use cortex_m_rt::exception;

    /// SysTick's largest reload value: it counts down from here (24 bits).
    const RELOAD: u32 = 0x00FF_FFFF;

    /// Times SysTick has wrapped (counted by its exception; each adds the handler's few
    /// instructions to the interval it falls in, once per 2^24 ticks).
    static WRAPS: AtomicU32 = AtomicU32::new(0);

    #[exception]
    fn SysTick() {
        // Only this handler writes (ARMv6-M has no atomic read-modify-write).
        WRAPS.store(
            WRAPS.load(Ordering::Relaxed).wrapping_add(1),
            Ordering::Relaxed,
        );
    }

    /// Starts SysTick on the core clock; `false` if the core peripherals are taken.
    pub(crate) fn start() -> bool {
        let Some(peripherals) = cortex_m::Peripherals::take() else {
            return false;
        };
        let mut syst = peripherals.SYST;
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(RELOAD);
        syst.clear_current();
        syst.enable_interrupt();
        syst.enable_counter();
        // Cleared, the counter reads 0 until its first reload.
        while SYST::get_current() == 0 {}
        true
    }

    /// SysTick ticks since it started, read consistently: a wrap that is pending or was
    /// counted during the read makes it read again.
    pub(crate) fn ticks() -> u64 {
        loop {
            let wraps = WRAPS.load(Ordering::SeqCst);
            let current = SYST::get_current();
            if WRAPS.load(Ordering::SeqCst) == wraps && !SCB::is_pendst_pending() {
                return (u64::from(wraps) << 24) + u64::from(RELOAD - current);
            }
        }
    }

    /// `cortex_m::asm::delay(n)`: n + 1 iterations of a two-instruction loop (`subs`, `bne`),
    /// always from this one call site (the loop's alignment padding, executed once, is then
    /// the same).
    #[inline(never)]
    pub(crate) fn spin(n: u32) {
        cortex_m::asm::delay(n);
    }
}

/// The counter on RISC-V: the machine-mode `minstret` (with `minstreth`), which qemu drives
/// from its virtual clock under `-icount` (and from the host's clock without it).
#[cfg(target_arch = "riscv32")]
mod counter {
    /// Nothing to start: the counter runs from reset in machine mode.
    pub(crate) fn start() -> bool {
        true
    }

    /// `minstreth:minstret`, read consistently (again if the high half moved).
    pub(crate) fn ticks() -> u64 {
        loop {
            let (high, low, again): (u32, u32, u32);
            // SAFETY: reading machine-mode counters, which the program runs in.
            unsafe {
                core::arch::asm!(
                    "csrr {0}, minstreth",
                    "csrr {1}, minstret",
                    "csrr {2}, minstreth",
                    out(reg) high,
                    out(reg) low,
                    out(reg) again,
                    options(nomem, nostack)
                );
            }
            if high == again {
                return (u64::from(high) << 32) | u64::from(low);
            }
        }
    }

    /// n + 1 iterations of a two-instruction loop (`addi`, `bnez`), as on the Cortex-M, always
    /// from this one call site.
    #[inline(never)]
    pub(crate) fn spin(n: u32) {
        // SAFETY: a register-only loop.
        unsafe {
            core::arch::asm!(
                "1:",
                "addi {0}, {0}, -1",
                "bnez {0}, 1b",
                inout(reg) n.wrapping_add(1) => _,
                options(nomem, nostack)
            );
        }
    }
}

use counter::{spin, ticks};

/// The ticks `f` takes, and its result.
fn measure<T>(f: impl FnOnce() -> T) -> (u64, T) {
    let start = ticks();
    let result = black_box(f());
    (ticks() - start, result)
}

/// Ticks per instruction, and the ticks of an empty bracket; `None` unless the calibration
/// loop's ticks grow in proportion to its length (not under `-icount`) and an instruction is at
/// least one tick (a coarser count would be rounded).
fn calibrate() -> Option<(f64, u64)> {
    // The least of three runs of each: a SysTick wrap adds its handler to the run it falls in.
    let least = |f: &dyn Fn() -> u64| (0..3).map(|_| f()).min().unwrap_or(0);
    let empty = least(&|| measure(|| ()).0);
    let [a, b, c] = [1, 2, 3].map(|k| least(&|| measure(|| spin(k * CALIBRATION)).0));
    // b − a and c − b are each CALIBRATION iterations. Where an instruction is a fraction of
    // ticks more than a whole number (3.2 on the M3's 12.5 MHz clock), each of the six readings
    // rounds down by under a tick: allow 4 ticks (a run without -icount is off by far more).
    let proportional = b > a && c > b && (c - b).abs_diff(b - a) <= 4;
    #[allow(clippy::cast_precision_loss)] // tick counts < 2^53
    let per_instruction = (c - a) as f64 / f64::from(4 * CALIBRATION);
    (proportional && per_instruction >= 1.0).then_some((per_instruction, empty))
}

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

/// Runs the day and fills `counts` (whole step, sun, sky, illuminance, CCT, drive; window and
/// roof every [`PLANE_EVERY`] steps); `Ok(false)` if a part's result differs from the whole
/// step's or a plane's light is not finite and non-negative.
fn run(counts: &mut [Counts; 8], per_instruction: f64, empty: u64) -> Result<bool, SkyError> {
    let (year, month, day) = DATE;
    let site = Site::new(SITE.0, SITE.1, SITE.2)?;
    let lamp = example_luminaire()?;
    let full_output: f32 = lamp.channels().iter().map(|c| c.full_output).sum();
    #[allow(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        clippy::cast_precision_loss
    )]
    let instructions = |t: u64| (t.saturating_sub(empty) as f64 / per_instruction + 0.5) as u32;
    let settings = Settings {
        aerosol_optical_depth: AOD,
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
        let (t_sky, sky) = measure(|| Daylight::new(sun.sun(), AOD));
        let sky = sky?;
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
            .zip([t_step, t_sun, t_sky, t_lux, t_cct, t_drive])
        {
            c.push(instructions(t));
        }
        if index % PLANE_EVERY == 0 {
            for (c, normal) in counts[6..].iter_mut().zip([WINDOW, ROOF]) {
                let (t, light) = measure(|| sky.tilted(normal));
                same &= light.is_finite() && light.min_element() >= 0.0;
                c.push(instructions(t));
            }
        }
    }
    Ok(same)
}

#[entry]
fn main() -> ! {
    if !counter::start() {
        hprintln!("controller-instructions: FAIL: the core peripherals are taken");
        qemu_check::finish(false)
    }

    let Some((per_instruction, empty)) = calibrate() else {
        hprintln!(
            "controller-instructions: FAIL: the counter does not count instructions; run \
             under qemu with -icount shift=8,align=off,sleep=off"
        );
        qemu_check::finish(false)
    };
    let part = |name| Counts {
        name,
        steps: [0; STEPS],
        measured: 0,
    };
    let mut counts = [
        part("controller::step"),
        part("  sun position (Grena 2012)"),
        part("  daylight (Daylight::new)"),
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
