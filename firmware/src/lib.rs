//! What every firmware example shares: the end of a run under qemu (the semihosting exit
//! status carries pass or fail), a panic or fault reported as a failure instead of a hang, the
//! entry point and semihosting output of the target's runtime, and numbers printed without
//! core's float formatting.
//!
//! Each example is a binary in `src/bin/` (or `src/main.rs`) that checks values computed on the
//! target against values `build.rs` computed on the host, prints its findings through
//! semihosting and ends with [`finish`]. The board, and so the memory map, follows from the
//! target (`build.rs`): `thumbv7em-none-eabihf` → mps2-an386 (Cortex-M4F),
//! `thumbv7m-none-eabi` → lm3s6965evb (Cortex-M3), `thumbv6m-none-eabi` → microbit (Cortex-M0),
//! `riscv32imac-unknown-none-elf` and `riscv32imc-unknown-none-elf` → qemu's `virt` (RV32).

#![no_std]

use core::fmt;
use core::panic::PanicInfo;

#[cfg(target_arch = "arm")]
pub use cortex_m_rt::entry;
#[cfg(target_arch = "arm")]
pub use cortex_m_semihosting::{debug, heprintln, hprintln};
#[cfg(target_arch = "riscv32")]
pub use riscv_rt::entry;
#[cfg(target_arch = "riscv32")]
pub use riscv_semihosting::{debug, heprintln, hprintln};

/// Ends the run: exit status 0 under qemu if `passed`, 1 otherwise.
pub fn finish(passed: bool) -> ! {
    debug::exit(if passed {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
    halt()
}

/// Ends a controller example: `outcome` is the number of steps that differed from the host's and
/// the number of steps, or the error that stopped the run; either is printed, and the run passes
/// only if no step differed.
pub fn finish_steps(example: &str, outcome: Result<(usize, usize), sky_core::SkyError>) -> ! {
    match outcome {
        Ok((failures, steps)) => {
            // As u32: each integer type's formatting is its own code in flash.
            #[allow(clippy::cast_possible_truncation)]
            let (failures_u32, steps_u32) = (failures as u32, steps as u32);
            hprintln!(
                "{} of {} steps differ from the host",
                Digits(failures_u32, 1),
                Digits(steps_u32, 1)
            );
            finish(failures == 0)
        }
        Err(error) => {
            hprintln!("{}: FAIL: {}", example, Message(error));
            finish(false)
        }
    }
}

/// A [`sky_core::SkyError`]'s message with its numbers as [`Decimal`]s (six decimals), so that
/// printing an error does not bring core's float formatting into flash.
pub struct Message(pub sky_core::SkyError);

impl fmt::Display for Message {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            // The one message with integers (`usize`), printed here by [`Digits`]: through
            // `write_message` it would link core's integer formatting.
            sky_core::SkyError::CapacityExceeded {
                collection,
                capacity,
                needed,
            } => write!(
                f,
                "{}: {} needed, but at most {} fit (fixed capacity, no allocation)",
                collection,
                Digits::of_usize(needed),
                Digits::of_usize(capacity)
            ),
            error => error.write_message(f, &|out, v| write!(out, "{}", Decimal(v, 6))),
        }
    }
}

/// `Digits(n, width)`: an unsigned integer in decimal with leading zeros to at least `width`
/// digits (at most 10), by the same digit loop as [`Decimal`]: core's integer formatting (its
/// digit-pair table and `pad_integral`) is never linked. The formatter's width and alignment
/// apply to the whole number (`{:>4}` right-aligns; plain `{:4}` pads on the right, as for text).
#[derive(Clone, Copy)]
pub struct Digits(pub u32, pub usize);

impl Digits {
    /// A `usize` (saturating at 2³² − 1, which no count here reaches), no leading zeros.
    pub fn of_usize(n: usize) -> Self {
        Self(u32::try_from(n).unwrap_or(u32::MAX), 1)
    }
}

impl fmt::Display for Digits {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut buffer = Buffer::default();
        buffer.push_digits(self.0, self.1);
        f.pad(buffer.as_str())
    }
}

/// `Decimal(value, digits)`: a number printed with `digits` (at most 9) digits after the point,
/// rounded, by integer formatting: core's float formatting (Grisu and Dragon, several KB of
/// flash) is never linked (docs/firmware.md, "Flash and RAM"). Whole parts from 2³² on print as
/// 4294967295; NaN and the infinities by name. The formatter's width and alignment
/// apply to the whole number.
#[derive(Clone, Copy)]
pub struct Decimal(pub f32, pub u32);

impl fmt::Display for Decimal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Self(value, digits) = *self;
        let digits = digits.min(9);
        if !value.is_finite() {
            return f.pad(if value.is_nan() {
                "NaN"
            } else if value > 0.0 {
                "inf"
            } else {
                "-inf"
            });
        }
        // Whole part and rounded fraction in u32 (no 64-bit division either); the whole part
        // saturates at 2³² − 1.
        let scale = 10u32.pow(digits);
        let magnitude = value.abs();
        #[allow(
            clippy::cast_precision_loss,
            clippy::cast_possible_truncation,
            clippy::cast_sign_loss
        )]
        let (mut whole, mut fraction) = {
            let whole = magnitude as u32;
            let rest = (magnitude - whole as f32).max(0.0);
            (whole, (rest * scale as f32 + 0.5) as u32)
        };
        if fraction >= scale {
            whole = whole.saturating_add(1);
            fraction -= scale;
        }
        let mut buffer = Buffer::default();
        if value.is_sign_negative() && (whole, fraction) != (0, 0) {
            buffer.push(b"-");
        }
        buffer.push_digits(whole, 1);
        if digits > 0 {
            buffer.push(b".");
            buffer.push_digits(fraction, digits as usize);
        }
        f.pad(buffer.as_str())
    }
}

/// A small stack buffer for [`Decimal`] (the longest is a sign, 10 digits, a point and 9),
/// filled digit by digit: no integer formatting of core either.
#[derive(Default)]
struct Buffer {
    bytes: [u8; 24],
    len: usize,
}

impl Buffer {
    /// Appends `bytes` (what does not fit is dropped).
    fn push(&mut self, bytes: &[u8]) {
        for &b in bytes {
            if let Some(slot) = self.bytes.get_mut(self.len) {
                *slot = b;
                self.len += 1;
            }
        }
    }

    /// Appends `n` in decimal, with leading zeros to at least `width` digits (at most 10).
    fn push_digits(&mut self, mut n: u32, width: usize) {
        let mut digits = [b'0'; 10];
        let mut start = digits.len();
        while n > 0 && start > 0 {
            start -= 1;
            #[allow(clippy::cast_possible_truncation)] // a digit
            let digit = (n % 10) as u8;
            digits[start] = b'0' + digit;
            n /= 10;
        }
        let start = start.min(digits.len().saturating_sub(width.max(1)));
        self.push(&digits[start..]);
    }

    /// Appends `n` as `0x` and eight hexadecimal digits.
    #[cfg(target_arch = "arm")]
    fn push_hex(&mut self, n: u32) {
        self.push(b"0x");
        for shift in (0..8).rev() {
            #[allow(clippy::cast_possible_truncation)] // a nibble
            let nibble = ((n >> (4 * shift)) & 0xf) as u8;
            self.push(&[if nibble < 10 {
                b'0' + nibble
            } else {
                b'a' + nibble - 10
            }]);
        }
    }

    fn as_str(&self) -> &str {
        core::str::from_utf8(&self.bytes[..self.len]).unwrap_or("?")
    }
}

/// Waits forever (reached only if the debugger resumes after an exit request).
fn halt() -> ! {
    loop {
        #[cfg(target_arch = "arm")]
        cortex_m::asm::wfi();
        #[cfg(target_arch = "riscv32")]
        riscv::asm::wfi();
    }
}

/// Reports a panic by where it happened (file and line) and fails. The message is not printed:
/// formatting it would link the formatting of every panic message in core (the bounds checks'
/// `usize`s among them) into flash; the location names the check. (On the Cortex-M0 a panic
/// never gets here: it is a trap, reported by the HardFault handler; `.cargo/config.toml`.)
#[panic_handler]
fn panic(info: &PanicInfo) -> ! {
    match info.location() {
        Some(at) => heprintln!("panic at {}:{}", at.file(), Digits(at.line(), 1)),
        None => heprintln!("panic"),
    }
    finish(false)
}

/// Reports a fault (with the faulting instruction's address, not the whole frame: its `Debug`
/// would bring core's struct formatting into flash) and fails, instead of hanging until qemu's
/// timeout.
#[cfg(target_arch = "arm")]
#[cortex_m_rt::exception]
unsafe fn HardFault(frame: &cortex_m_rt::ExceptionFrame) -> ! {
    let mut pc = Buffer::default();
    pc.push_hex(frame.pc());
    heprintln!("hard fault at pc {}", pc.as_str());
    finish(false)
}
