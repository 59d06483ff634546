//! The GPU context: adapter choice, device and queue.
//!
//! The adapter is chosen the way wgpu's `util::initialize_adapter_from_env_or_default`
//! does it, with clearer errors and a ranking suited to compute:
//! - `WGPU_BACKEND` (e.g. `vulkan`, `gl`, `vulkan,gl`) limits the backends tried;
//! - `WGPU_ADAPTER_NAME` keeps only adapters whose name contains it (case-insensitive;
//!   an error naming the adapters found when none matches, where wgpu panics);
//! - adapters that cannot run the solver (no compute shaders, too few storage buffers
//!   per stage, no `SHADER_F64` when f64 is asked for) are set aside, with the reason;
//! - the rest are ranked: discrete GPU, integrated GPU (first with
//!   `WGPU_POWER_PREF=low`), virtual GPU, CPU (software: lavapipe, llvmpipe, WARP),
//!   then other; ties go to Vulkan, Metal or DX12 over GL, then to `SHADER_F64`.
//!
//! When nothing is usable, [`GpuContext::new`] returns [`Error::NoAdapter`] with every
//! adapter seen and why it was set aside. The probe prints nothing (the adapters seen
//! are logged at debug level; see also `quiet_device_select`).

use crate::error::Error;
use crate::options::Precision;
use std::sync::{Arc, Mutex};

/// Storage buffers the solver binds in one stage (see the prelude's bindings: 0, 2 to
/// 16 and 18, and the waves' 17, 19, 20 and 21; binding 1 is a uniform).
pub const STORAGE_BUFFERS_PER_STAGE: u32 = 21;

/// An open device, its queue, and what the adapter is.
#[derive(Clone, Debug)]
pub struct GpuContext {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// The adapter's description.
    pub info: wgpu::AdapterInfo,
    /// Whether the device was opened with `SHADER_F64` (f64 shaders are usable).
    pub shader_f64: bool,
    /// The device limits in force.
    pub limits: wgpu::Limits,
    /// The first uncaptured device error, if any (validation, out of memory, lost).
    errors: Arc<Mutex<Option<String>>>,
}

/// What makes an adapter unusable, or `None` when it can run the solver.
fn unusable(adapter: &wgpu::Adapter, need_f64: bool) -> Option<String> {
    let down = adapter.get_downlevel_capabilities();
    if !down.flags.contains(wgpu::DownlevelFlags::COMPUTE_SHADERS) {
        return Some("no compute shaders".into());
    }
    let lim = adapter.limits();
    if lim.max_storage_buffers_per_shader_stage < STORAGE_BUFFERS_PER_STAGE {
        return Some(format!(
            "{} storage buffers per stage, {} needed",
            lim.max_storage_buffers_per_shader_stage, STORAGE_BUFFERS_PER_STAGE
        ));
    }
    if need_f64 && !adapter.features().contains(wgpu::Features::SHADER_F64) {
        return Some("no SHADER_F64 (f64 was asked for)".into());
    }
    None
}

/// Keeps the adapter probe quiet without a desktop session.
///
/// Mesa's Vulkan device-select layer (an implicit layer, loaded into every Vulkan
/// instance) opens a Wayland connection while listing devices, to put the one driving
/// the display first; with no session (`XDG_RUNTIME_DIR` unset: servers, CI,
/// containers) libwayland prints `error: XDG_RUNTIME_DIR is invalid or not set in the
/// environment.` to stderr, twice, on a run that then goes well. The ranking here does
/// not use the layer's order, so without a session the layer is switched off by its own
/// switch, `NODEVICE_SELECT=1`, unless the user set that variable. It is set once,
/// before the first instance, when no other thread of the library reads the
/// environment.
fn quiet_device_select() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let no_session = std::env::var_os("XDG_RUNTIME_DIR").is_none_or(|v| v.is_empty());
        if no_session && std::env::var_os("NODEVICE_SELECT").is_none() {
            std::env::set_var("NODEVICE_SELECT", "1");
        }
    });
}

/// Ranking key of a usable adapter: larger is better.
fn rank(info: &wgpu::AdapterInfo, f64_ok: bool, low_power: bool) -> (u8, u8, u8) {
    use wgpu::DeviceType::*;
    let ty = match info.device_type {
        DiscreteGpu if low_power => 3,
        DiscreteGpu => 4,
        IntegratedGpu if low_power => 4,
        IntegratedGpu => 3,
        VirtualGpu => 2,
        Cpu => 1,
        Other => 0,
    };
    let backend = match info.backend {
        wgpu::Backend::Vulkan | wgpu::Backend::Metal | wgpu::Backend::Dx12 => 1,
        _ => 0,
    };
    (ty, backend, f64_ok as u8)
}

/// One line describing an adapter: `name (backend, type, driver info)`.
pub fn describe(info: &wgpu::AdapterInfo) -> String {
    let driver = [info.driver.as_str(), info.driver_info.as_str()]
        .iter()
        .filter(|s| !s.is_empty())
        .copied()
        .collect::<Vec<_>>()
        .join(" ");
    format!(
        "{} ({:?}, {:?}{}{})",
        info.name,
        info.backend,
        info.device_type,
        if driver.is_empty() { "" } else { ", " },
        driver
    )
}

impl GpuContext {
    /// Opens the best usable adapter (see the module doc). With `need_f64`, only
    /// adapters with `SHADER_F64` qualify. `SHADER_F64` is enabled whenever the
    /// adapter has it, so one context can run both precisions.
    pub fn new(need_f64: bool) -> Result<Self, Error> {
        pollster::block_on(Self::new_async(need_f64))
    }

    async fn new_async(need_f64: bool) -> Result<Self, Error> {
        quiet_device_select();
        let desc = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
        let backends = desc.backends;
        let instance = wgpu::Instance::new(desc);
        let adapters = instance.enumerate_adapters(backends).await;
        let name_filter = std::env::var("WGPU_ADAPTER_NAME")
            .ok()
            .map(|s| s.to_lowercase())
            .filter(|s| !s.is_empty());
        let low_power = wgpu::PowerPreference::from_env() == Some(wgpu::PowerPreference::LowPower);
        let mut seen = Vec::new();
        let mut best: Option<((u8, u8, u8), wgpu::Adapter)> = None;
        for a in adapters {
            let info = a.get_info();
            let d = describe(&info);
            if let Some(f) = &name_filter {
                if !info.name.to_lowercase().contains(f.as_str()) {
                    seen.push(format!("{d}: name does not match WGPU_ADAPTER_NAME"));
                    continue;
                }
            }
            if let Some(why) = unusable(&a, need_f64) {
                seen.push(format!("{d}: {why}"));
                continue;
            }
            let f64_ok = a.features().contains(wgpu::Features::SHADER_F64);
            let key = rank(&info, f64_ok, low_power);
            seen.push(format!("{d}: usable"));
            if best.as_ref().is_none_or(|(k, _)| key > *k) {
                best = Some((key, a));
            }
        }
        let Some((_, adapter)) = best else {
            let env = |k: &str| std::env::var(k).map(|v| format!("{k}={v}")).ok();
            let envs: Vec<String> = ["WGPU_BACKEND", "WGPU_ADAPTER_NAME"]
                .iter()
                .filter_map(|k| env(k))
                .collect();
            return Err(Error::NoAdapter(format!(
                "no usable adapter{}{}; adapters seen: {}",
                if need_f64 { " with SHADER_F64" } else { "" },
                if envs.is_empty() {
                    String::new()
                } else {
                    format!(" with {}", envs.join(", "))
                },
                if seen.is_empty() {
                    "none (on Linux, `apt-get install mesa-vulkan-drivers libvulkan1` gives the lavapipe software adapter)".into()
                } else {
                    seen.join("; ")
                }
            )));
        };
        for s in &seen {
            log::debug!("adapter {s}");
        }
        let info = adapter.get_info();
        let shader_f64 = adapter.features().contains(wgpu::Features::SHADER_F64);
        let alim = adapter.limits();
        let limits = wgpu::Limits {
            max_storage_buffers_per_shader_stage: STORAGE_BUFFERS_PER_STAGE,
            max_storage_buffer_binding_size: alim.max_storage_buffer_binding_size,
            max_buffer_size: alim.max_buffer_size,
            // The fused kernel keeps a block's state in workgroup memory: as much as the
            // adapter has (32 KiB on lavapipe, 48 KiB and more on discrete GPUs).
            max_compute_workgroup_storage_size: alim
                .max_compute_workgroup_storage_size
                .max(wgpu::Limits::downlevel_defaults().max_compute_workgroup_storage_size),
            ..wgpu::Limits::downlevel_defaults()
        }
        .using_alignment(alim.clone());
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("cablesim"),
                required_features: if shader_f64 {
                    wgpu::Features::SHADER_F64
                } else {
                    wgpu::Features::empty()
                },
                required_limits: limits.clone(),
                ..Default::default()
            })
            .await
            .map_err(|e| {
                Error::NoAdapter(format!("{}: cannot open a device: {e}", describe(&info)))
            })?;
        let errors = Arc::new(Mutex::new(None));
        let sink = errors.clone();
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            log::error!("GPU error: {e}");
            let mut g = sink.lock().unwrap_or_else(|p| p.into_inner());
            g.get_or_insert_with(|| e.to_string());
        }));
        log::debug!(
            "GPU adapter: {}{}",
            describe(&info),
            if shader_f64 { ", SHADER_F64" } else { "" }
        );
        Ok(Self {
            device,
            queue,
            info,
            shader_f64,
            limits,
            errors,
        })
    }

    /// The adapter's description (name, backend, type, driver).
    pub fn describe(&self) -> String {
        describe(&self.info)
    }

    /// Whether shaders at precision `p` can run on this device.
    pub fn supports(&self, p: Precision) -> bool {
        p == Precision::F32 || self.shader_f64
    }

    /// Takes the first uncaptured device error since the last call, as an [`Error::Gpu`].
    pub fn take_error(&self) -> Result<(), Error> {
        let mut g = self.errors.lock().unwrap_or_else(|p| p.into_inner());
        match g.take() {
            Some(e) => Err(Error::Gpu(e)),
            None => Ok(()),
        }
    }
}
