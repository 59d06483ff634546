//! The Rust twins of the WGSL structs (`cablesim::gpu::layout`) match the WGSL
//! (`shaders/shared/prelude.wgsl`) member by member: names, offsets and sizes as naga
//! lays them out, at both precisions, and every struct the shaders bind has a twin.

use cablesim::gpu::layout::{all_structs, Field, GpuReal};
use cablesim::gpu::shaders;
use cablesim::gpu::Precision;
use std::collections::HashMap;

/// `name -> (size, members)` of WGSL structs.
type Structs = HashMap<String, (usize, Vec<Field>)>;

/// Every WGSL struct of the prelude at precision `p`, and the names of the structs
/// that bindings use.
fn wgsl_structs(p: Precision) -> (Structs, Vec<String>) {
    let src = shaders::prelude(p);
    let module = naga::front::wgsl::parse_str(&src)
        .unwrap_or_else(|e| panic!("prelude ({}):\n{}", p.name(), e.emit_to_string(&src)));
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).expect("layout");
    let mut out = HashMap::new();
    for (_, ty) in module.types.iter() {
        if let naga::TypeInner::Struct { members, span } = &ty.inner {
            let name = ty.name.clone().expect("named struct");
            let fields = members
                .iter()
                .map(|m| Field {
                    name: Box::leak(m.name.clone().unwrap_or_default().into_boxed_str()),
                    offset: m.offset as usize,
                    size: layouter[m.ty].size as usize,
                })
                .collect();
            out.insert(name, (*span as usize, fields));
        }
    }
    let mut bound = Vec::new();
    for (_, g) in module.global_variables.iter() {
        let mut ty = &module.types[g.ty];
        if let naga::TypeInner::Array { base, .. } = ty.inner {
            ty = &module.types[base];
        }
        if let (naga::TypeInner::Struct { .. }, Some(n)) = (&ty.inner, &ty.name) {
            bound.push(n.clone());
        }
    }
    (out, bound)
}

fn check<R: GpuReal>(p: Precision) {
    let (wgsl, bound) = wgsl_structs(p);
    let rust = all_structs::<R>();
    for (name, size, fields) in &rust {
        let (wsize, wfields) = wgsl
            .get(*name)
            .unwrap_or_else(|| panic!("{}: WGSL has no struct {name}", p.name()));
        assert_eq!(
            wfields,
            fields,
            "{}: struct {name}: WGSL members (left) differ from Rust (right)",
            p.name()
        );
        assert_eq!(
            wsize,
            size,
            "{}: struct {name}: WGSL size vs Rust size",
            p.name()
        );
        // No gaps: Pod would be unsound with padding, and a gap means the sides drift.
        let mut end = 0;
        for f in fields {
            assert_eq!(
                f.offset,
                end,
                "{}: {name}.{}: gap before it",
                p.name(),
                f.name
            );
            end += f.size;
        }
        assert_eq!(end, *size, "{}: {name}: tail padding", p.name());
    }
    for b in &bound {
        assert!(
            rust.iter().any(|(n, _, _)| n == b),
            "{}: the shaders bind struct {b}, which has no Rust twin in gpu::layout",
            p.name()
        );
    }
    assert!(bound.len() >= 10, "bindings found: {bound:?}");
}

#[test]
fn rust_and_wgsl_structs_agree_in_f32() {
    check::<f32>(Precision::F32);
}

#[test]
fn rust_and_wgsl_structs_agree_in_f64() {
    check::<f64>(Precision::F64);
}
