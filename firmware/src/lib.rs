//! What every firmware example shares: the end of a run under qemu (the semihosting exit
//! status carries pass or fail), and a panic or fault reported as a failure instead of a hang.
//!
//! Each example is a binary in `src/bin/` (or `src/main.rs`) that checks values computed on the
//! target against values `build.rs` computed on the host, prints its findings through
//! semihosting and ends with [`finish`]. The board, and so the memory map, follows from the
//! target (`build.rs`): `thumbv7em-none-eabihf` → mps2-an386 (Cortex-M4F),
//! `thumbv7m-none-eabi` → lm3s6965evb (Cortex-M3), `thumbv6m-none-eabi` → microbit (Cortex-M0).

#![no_std]

use core::panic::PanicInfo;

use cortex_m_rt::{ExceptionFrame, exception};
use cortex_m_semihosting::{debug, heprintln, hprintln};

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
            hprintln!("{} of {} steps differ from the host", failures, steps);
            finish(failures == 0)
        }
        Err(error) => {
            hprintln!("{}: FAIL: {}", example, error);
            finish(false)
        }
    }
}

/// Waits forever (reached only if the debugger resumes after an exit request).
fn halt() -> ! {
    loop {
        cortex_m::asm::wfi();
    }
}

#[panic_handler]
fn panic(info: &PanicInfo) -> ! {
    heprintln!("panic: {}", info);
    finish(false)
}

/// Reports a fault and fails, instead of hanging until qemu's timeout.
#[exception]
unsafe fn HardFault(frame: &ExceptionFrame) -> ! {
    heprintln!("hard fault: {:?}", frame);
    finish(false)
}
