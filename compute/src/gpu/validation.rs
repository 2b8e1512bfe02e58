//! The debug-utils messenger: counts validation errors so tests can fail on any of them.

use ash::vk;
use std::ffi::CStr;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::Mutex;

/// Name of the Khronos validation layer.
pub const VALIDATION_LAYER: &CStr = c"VK_LAYER_KHRONOS_validation";

/// What the validation layer reported over the lifetime of one device.
///
/// It outlives the device on purpose: leaks are reported at `vkDestroyDevice`, so a test reads
/// the log after dropping its [`Gpu`](crate::gpu::Gpu).
#[derive(Debug, Default)]
pub struct ValidationLog {
    errors: AtomicU32,
    warnings: AtomicU32,
    messages: Mutex<Vec<String>>,
}

impl ValidationLog {
    /// Number of validation errors reported so far.
    pub fn errors(&self) -> u32 {
        self.errors.load(Ordering::SeqCst)
    }

    /// Number of validation warnings reported so far.
    pub fn warnings(&self) -> u32 {
        self.warnings.load(Ordering::SeqCst)
    }

    /// The first error and warning messages (at most 32 are kept).
    pub fn messages(&self) -> Vec<String> {
        self.messages.lock().unwrap().clone()
    }

    fn record(&self, severity: vk::DebugUtilsMessageSeverityFlagsEXT, text: String) {
        if severity.contains(vk::DebugUtilsMessageSeverityFlagsEXT::ERROR) {
            self.errors.fetch_add(1, Ordering::SeqCst);
            log::error!("Vulkan validation: {text}");
        } else {
            self.warnings.fetch_add(1, Ordering::SeqCst);
            log::warn!("Vulkan validation: {text}");
        }
        let mut messages = self.messages.lock().unwrap();
        if messages.len() < 32 {
            messages.push(text);
        }
    }
}

/// Messenger callback; `user_data` is a `*const ValidationLog` kept alive by the context.
pub(crate) unsafe extern "system" fn messenger_callback(
    severity: vk::DebugUtilsMessageSeverityFlagsEXT,
    types: vk::DebugUtilsMessageTypeFlagsEXT,
    data: *const vk::DebugUtilsMessengerCallbackDataEXT<'_>,
    user_data: *mut std::ffi::c_void,
) -> vk::Bool32 {
    let interesting = severity.intersects(
        vk::DebugUtilsMessageSeverityFlagsEXT::ERROR
            | vk::DebugUtilsMessageSeverityFlagsEXT::WARNING,
    ) && types.intersects(
        vk::DebugUtilsMessageTypeFlagsEXT::VALIDATION
            | vk::DebugUtilsMessageTypeFlagsEXT::PERFORMANCE,
    );
    if interesting && !data.is_null() && !user_data.is_null() {
        let data = unsafe { &*data };
        let text = if data.p_message.is_null() {
            String::from("(no message)")
        } else {
            unsafe { CStr::from_ptr(data.p_message) }
                .to_string_lossy()
                .into_owned()
        };
        let log = unsafe { &*(user_data as *const ValidationLog) };
        log.record(severity, text);
    }
    vk::FALSE
}
