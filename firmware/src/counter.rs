//! The executed-instruction counter of the instruction-counting examples
//! (`src/bin/controller_instructions.rs`, `src/bin/calibration_instructions.rs`), included by
//! each as `mod counter`.
//!
//! Under qemu with `-icount shift=N,align=off,sleep=off` every executed instruction advances the
//! virtual clock by exactly 2^N ns, so a counter of that clock counts instructions: SysTick,
//! counting the core clock, on a Cortex-M; `minstret`, which qemu reads from the virtual clock,
//! on RISC-V. The ticks per instruction are calibrated on a loop of two instructions per
//! iteration ([`calibrate`]); a run without `-icount` fails that calibration.

use core::hint::black_box;

/// Iterations of the calibration loop (two instructions each).
const CALIBRATION: u32 = 200_000;

/// The clock on a Cortex-M: SysTick, counting the core clock down from its 24-bit reload.
#[cfg(target_arch = "arm")]
mod clock {
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

/// The clock on RISC-V: the machine-mode `minstret` (with `minstreth`), which qemu drives
/// from its virtual clock under `-icount` (and from the host's clock without it).
#[cfg(target_arch = "riscv32")]
mod clock {
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

use clock::{spin, ticks};

/// The ticks `f` takes, and its result.
pub(crate) fn measure<T>(f: impl FnOnce() -> T) -> (u64, T) {
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

/// The instructions of a bracket of `ticks` counter ticks, by the calibration's ticks per
/// instruction and empty bracket ([`calibrate`]).
#[allow(
    clippy::cast_possible_truncation,
    clippy::cast_sign_loss,
    clippy::cast_precision_loss
)]
pub(crate) fn instructions(ticks: u64, per_instruction: f64, empty: u64) -> u32 {
    (ticks.saturating_sub(empty) as f64 / per_instruction + 0.5) as u32
}

/// Starts the counter and calibrates it ([`calibrate`]): the ticks per instruction and of an
/// empty bracket. On failure (the core peripherals taken, or no `-icount`) prints why, naming
/// `example`, and ends the run as failed.
pub(crate) fn start(example: &str) -> (f64, u64) {
    if !clock::start() {
        qemu_check::hprintln!("{}: FAIL: the core peripherals are taken", example);
        qemu_check::finish(false)
    }
    let Some(calibration) = calibrate() else {
        qemu_check::hprintln!(
            "{}: FAIL: the counter does not count instructions; run under qemu with -icount \
             shift=8,align=off,sleep=off",
            example
        );
        qemu_check::finish(false)
    };
    calibration
}
