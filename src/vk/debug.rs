//! Debug messenger: maps Vulkan message severity to log levels and counts validation warnings
//! and errors (the test canary).

use ash::vk;
use std::ffi::{c_void, CStr};
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::Mutex;

/// Counts validation and performance messages of warning or error severity.
#[derive(Default, Debug)]
pub struct ValidationCanary {
    count: AtomicU32,
    messages: Mutex<Vec<String>>,
}

impl ValidationCanary {
    /// Number of validation warnings and errors seen so far.
    pub fn count(&self) -> u32 {
        self.count.load(Ordering::SeqCst)
    }

    /// The first messages seen (at most 16), for failure reports.
    pub fn messages(&self) -> Vec<String> {
        self.messages.lock().unwrap_or_else(|e| e.into_inner()).clone()
    }

    /// The count and first messages seen so far, counting afresh from now (a context shared
    /// by several tests checks each test's messages alone).
    pub fn take(&self) -> (u32, Vec<String>) {
        let mut m = self.messages.lock().unwrap_or_else(|e| e.into_inner());
        (self.count.swap(0, Ordering::SeqCst), std::mem::take(&mut *m))
    }

    fn record(&self, text: String) {
        self.count.fetch_add(1, Ordering::SeqCst);
        let mut m = self.messages.lock().unwrap_or_else(|e| e.into_inner());
        if m.len() < 16 {
            m.push(text);
        }
    }
}

/// The callback handed to `VK_EXT_debug_utils`; `user` points at the context's `ValidationCanary`.
pub(crate) unsafe extern "system" fn messenger_callback(
    severity: vk::DebugUtilsMessageSeverityFlagsEXT,
    kind: vk::DebugUtilsMessageTypeFlagsEXT,
    data: *const vk::DebugUtilsMessengerCallbackDataEXT<'_>,
    user: *mut c_void,
) -> vk::Bool32 {
    // SAFETY: the layer passes a valid callback-data pointer for the duration of the call; its
    // message is a NUL-terminated string or null.
    let text = unsafe {
        data.as_ref()
            .filter(|d| !d.p_message.is_null())
            .map(|d| CStr::from_ptr(d.p_message).to_string_lossy().into_owned())
            .unwrap_or_default()
    };
    let counted = kind.intersects(
        vk::DebugUtilsMessageTypeFlagsEXT::VALIDATION | vk::DebugUtilsMessageTypeFlagsEXT::PERFORMANCE,
    ) && severity.intersects(
        vk::DebugUtilsMessageSeverityFlagsEXT::WARNING | vk::DebugUtilsMessageSeverityFlagsEXT::ERROR,
    );
    if counted {
        // SAFETY: `user` is the address of the ValidationCanary inside an Arc that the context
        // keeps alive until after the messenger is destroyed.
        if let Some(canary) = unsafe { (user as *const ValidationCanary).as_ref() } {
            canary.record(text.clone());
        }
    }
    if severity.contains(vk::DebugUtilsMessageSeverityFlagsEXT::ERROR) {
        log::error!("vulkan validation: {text}");
    } else if severity.contains(vk::DebugUtilsMessageSeverityFlagsEXT::WARNING) {
        log::warn!("vulkan: {text}");
    } else if severity.contains(vk::DebugUtilsMessageSeverityFlagsEXT::INFO) {
        log::debug!("vulkan: {text}");
    } else {
        log::trace!("vulkan: {text}");
    }
    vk::FALSE
}
