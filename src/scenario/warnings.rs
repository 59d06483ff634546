//! Where a scenario's warnings go: to the log (`log::warn!`), or, while
//! [`collect_warnings`] runs, into a list its caller reads.
//!
//! A study builds one scenario per member from the same base and sea state: the base's
//! warnings (an unused line type, a steep sea state) would be logged once per member,
//! thirty or a thousand times. The study checks each sea state's scenario once with the
//! warnings collected, logs them once under the study's own field names, and builds its
//! members with the warnings collected and dropped. Validation is single-threaded within
//! one parse, so a thread-local list is enough: members parsed on other threads at the
//! same time keep their own.

use std::cell::RefCell;

thread_local! {
    /// The warnings kept while [`collect_warnings`] runs on this thread (`None`: log
    /// them).
    pub static SINK: RefCell<Option<Vec<String>>> = const { RefCell::new(None) };
}

/// Logs `message` as a warning, or keeps it when [`collect_warnings`] is running on
/// this thread.
pub fn warn(message: String) {
    let kept = SINK.with(|s| match s.borrow_mut().as_mut() {
        Some(list) => {
            list.push(message.clone());
            true
        }
        None => false,
    });
    if !kept {
        log::warn!("{message}");
    }
}

/// Runs `f` with this thread's scenario warnings kept instead of logged; returns its
/// result and the warnings in the order they were raised.
pub fn collect_warnings<T>(f: impl FnOnce() -> T) -> (T, Vec<String>) {
    let outer = SINK.with(|s| s.borrow_mut().replace(Vec::new()));
    let out = f();
    let kept = SINK.with(|s| std::mem::replace(&mut *s.borrow_mut(), outer));
    (out, kept.unwrap_or_default())
}
