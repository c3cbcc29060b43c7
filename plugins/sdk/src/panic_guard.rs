//! Catching a law's panics at the C boundary without printing them: Rust's default panic hook
//! would print every panic to stderr before `catch_unwind` returns (a law that panics at every
//! point of an interface printed 77 messages). Inside [`guarded`] the hook records where the
//! panic happened instead; the message and place travel back to the host as the call's error,
//! and the host reports each distinct failure once. Outside it the previous hook runs as before.

use std::cell::{Cell, RefCell};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Once;

thread_local! {
    static INSIDE_LAW: Cell<bool> = const { Cell::new(false) };
    static PANIC_PLACE: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// Installs (once per process, or per plugin library, which has its own standard library) the
/// hook that stays quiet inside [`guarded`] and defers to the previous hook elsewhere.
fn install_quiet_hook() {
    static INSTALL: Once = Once::new();
    INSTALL.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if INSIDE_LAW.with(Cell::get) {
                let place = info.location().map(|l| format!("{}:{}", l.file(), l.line()));
                PANIC_PLACE.with(|p| *p.borrow_mut() = place);
            } else {
                previous(info);
            }
        }));
    });
}

/// Runs `f`, catching a panic; on a panic returns its message and, when known, where it was
/// raised ("message (at src/lib.rs:12)").
pub fn guarded<R>(f: impl FnOnce() -> R) -> Result<R, String> {
    install_quiet_hook();
    let was_inside = INSIDE_LAW.with(|inside| inside.replace(true));
    let result = catch_unwind(AssertUnwindSafe(f));
    INSIDE_LAW.with(|inside| inside.set(was_inside));
    result.map_err(|payload| {
        let text = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown panic".into());
        match PANIC_PLACE.with(|p| p.borrow_mut().take()) {
            Some(place) => format!("{text} (at {place})"),
            None => text,
        }
    })
}

#[cfg(test)]
mod tests {
    use super::guarded;

    #[test]
    fn a_panic_becomes_its_message_with_the_place() {
        let r: Result<(), String> = guarded(|| panic!("bad gap {}", 3));
        let message = r.unwrap_err();
        assert!(message.starts_with("bad gap 3 (at ") && message.contains("panic_guard.rs"), "{message}");
        assert_eq!(guarded(|| 7), Ok(7));
    }
}
