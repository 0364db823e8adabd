//! The frame graph checked against the shaders' reflection: every global an entry point uses
//! bound to a resource of the right kind, dimension and format, counter indices equal to the
//! WGSL's constants, passes named once under any plan options. Build time (`stratus-shaders`
//! runs it before writing the manifest); the graph's types ([`crate::desc`]) do not depend on
//! the manifest's, so the manifest can carry the checked graph.

use std::collections::BTreeSet;

use crate::{
    desc::*,
    manifest::{Access, BindingKind, Manifest, ModuleManifest, Stage},
};

impl GraphDesc {
    /// Checks the graph against the reflection of the modules it names; `constant` looks up
    /// the value of a WGSL `const` in a module (for the counters' indices), where the caller
    /// has the compiled modules (build time); pass `None` to skip that part.
    pub fn check(
        &self,
        manifest: &Manifest,
        origin: &str,
        constant: Option<&ConstantLookup<'_>>,
    ) -> Result<(), GraphError> {
        let mut p = Vec::new();
        let mut names = BTreeSet::new();
        for r in &self.resources {
            let at = format!("resource `{}`", r.name);
            if !names.insert(r.name.as_str()) {
                p.push(format!("{at} is declared twice"));
            }
            if r.name.is_empty() || r.name.contains(PREVIOUS) {
                p.push(format!(
                    "{at}: a name may not be empty or contain `{PREVIOUS}`"
                ));
            }
            check_resource(r, &at, &mut p);
        }
        let mut pass_names = BTreeSet::new();
        for pass in &self.passes {
            let at = format!("pass `{}`", pass.name);
            if !pass_names.insert(pass.name.as_str()) {
                // Allowed for passes that no combination of plan options plans together.
                let same: Vec<&PassDesc> =
                    self.passes.iter().filter(|q| q.name == pass.name).collect();
                let together = (0..1u32 << PLAN_OPTIONS.len()).any(|bits| {
                    let set = |name: &str| {
                        PLAN_OPTIONS
                            .iter()
                            .position(|o| *o == name)
                            .is_some_and(|i| bits & (1 << i) != 0)
                    };
                    same.iter()
                        .filter(|q| {
                            q.plan
                                .as_deref()
                                .is_none_or(|c| plan_condition_holds(c, &set))
                        })
                        .count()
                        > 1
                });
                // Once per name: at its second declaration.
                if together
                    && same
                        .get(1)
                        .is_some_and(|second| std::ptr::eq(*second, pass))
                {
                    p.push(format!(
                        "{at} is declared more than once, and some plan options plan two of them (passes may share a name only under exclusive `plan` conditions)"
                    ));
                }
            }
            if let Some(condition) = &pass.plan {
                for term in condition.split('&') {
                    let name = term.trim().trim_start_matches('!').trim();
                    if !PLAN_OPTIONS.contains(&name) {
                        p.push(format!(
                            "{at}: `plan = \"{condition}\"` names `{name}`, which is no plan option (known: {})",
                            PLAN_OPTIONS.join(", ")
                        ));
                    }
                }
            }
            let Some(module) = manifest.module(&pass.module) else {
                p.push(format!(
                    "{at}: module `{}` is not in wgsl/modules.toml",
                    pass.module
                ));
                continue;
            };
            self.check_pass(pass, module, &at, &mut p);
        }
        if let Some(constant) = constant {
            for r in self.resources.iter().filter(|r| !r.counters.is_empty()) {
                let modules: BTreeSet<&str> = self
                    .passes
                    .iter()
                    .filter(|pass| pass.bind.values().any(|v| v == &r.name))
                    .map(|pass| pass.module.as_str())
                    .collect();
                for (i, c) in r.counters.iter().enumerate() {
                    for m in &modules {
                        match constant(m, &c.wgsl) {
                            Some(v) if v == i as f64 => {}
                            Some(v) => p.push(format!(
                                "resource `{}`: counter `{}` is number {i} here, but `{}` in module `{m}` is {v}",
                                r.name, c.name, c.wgsl
                            )),
                            None => p.push(format!(
                                "resource `{}`: counter `{}` names `{}`, which module `{m}` does not declare",
                                r.name, c.name, c.wgsl
                            )),
                        }
                    }
                }
            }
        }
        if p.is_empty() {
            Ok(())
        } else {
            Err(GraphError {
                origin: origin.into(),
                problems: p,
            })
        }
    }

    fn check_pass(&self, pass: &PassDesc, module: &ModuleManifest, at: &str, p: &mut Vec<String>) {
        let mut entries = Vec::new();
        let mut stage_of = |name: &Option<String>, stage: Stage, p: &mut Vec<String>| {
            if let Some(name) = name {
                match module.entry_point(name) {
                    Some(ep) if ep.stage == stage => entries.push(ep),
                    Some(ep) => p.push(format!(
                        "{at}: entry point `{name}` is a {:?} shader, not {stage:?}",
                        ep.stage
                    )),
                    None => p.push(format!(
                        "{at}: module `{}` has no entry point `{name}`",
                        module.name
                    )),
                }
            }
        };
        stage_of(&pass.compute, Stage::Compute, p);
        stage_of(&pass.vertex, Stage::Vertex, p);
        stage_of(&pass.fragment, Stage::Fragment, p);
        let raster = pass.vertex.is_some() || pass.fragment.is_some();
        match (pass.compute.is_some(), raster) {
            (true, true) => p.push(format!(
                "{at}: a pass is compute (`compute`) or raster (`vertex` + `fragment`), not both"
            )),
            (false, false) => p.push(format!(
                "{at}: names no entry point (`compute`, or `vertex` and `fragment`)"
            )),
            (false, true) if pass.vertex.is_none() || pass.fragment.is_none() => p.push(format!(
                "{at}: a raster pass needs both `vertex` and `fragment`"
            )),
            (false, true) if pass.color.is_empty() && pass.depth.is_none() => p.push(format!(
                "{at}: a raster pass needs a `color` or `depth` target"
            )),
            (true, false) if !pass.color.is_empty() || pass.depth.is_some() => {
                p.push(format!("{at}: a compute pass has no raster targets"))
            }
            _ => {}
        }
        if let Some(name) = pass
            .when
            .as_deref()
            .map(|w| w.trim().trim_start_matches('!').trim())
            .and_then(|w| w.strip_prefix("stale:"))
        {
            let computed = self
                .resource(name)
                .is_some_and(|r| r.lifetime == Lifetime::Persistent && r.upload.is_none());
            if !computed {
                p.push(format!(
                    "{at}: `when = \"stale:{name}\"` names no computed persistent resource (lifetime = \"persistent\", not uploaded)"
                ));
            }
        }
        if raster && pass.vertices == 0 {
            p.push(format!("{at}: `vertices` must be at least 1"));
        }
        if let Err(e) = pass.extent.resolve(1, 1) {
            p.push(format!("{at}: {e}"));
        }
        // Every global the entry points use must be bound, and every binding used.
        let mut used = BTreeSet::new();
        for ep in &entries {
            used.extend(ep.uses.iter().copied());
        }
        for &[group, binding] in &used {
            let Some(info) = module.resource_at(group, binding) else {
                p.push(format!(
                    "{at}: uses @group({group}) @binding({binding}), which the manifest lacks"
                ));
                continue;
            };
            match pass.bind.get(&info.name) {
                None => p.push(format!(
                    "{at}: the WGSL uses `{}` (@group({group}) @binding({binding})), which `bind` does not name",
                    info.name
                )),
                Some(target) => self.check_binding(info, target, at, p),
            }
        }
        for name in pass.bind.keys() {
            let is_used = module
                .resources
                .iter()
                .any(|r| &r.name == name && used.contains(&[r.group, r.binding]));
            if !is_used {
                p.push(format!(
                    "{at}: binds `{name}`, which its entry points do not use"
                ));
            }
        }
        for c in &pass.color {
            match self.resource(&c.target) {
                Some(r)
                    if r.kind == ResourceKind::Texture
                        && r.dimension.unwrap_or(Dimension::D2) == Dimension::D2
                        && r.format.is_some_and(|f| !f.is_depth()) => {}
                _ => p.push(format!(
                    "{at}: colour target `{}` must be a 2d texture resource of a colour format",
                    c.target
                )),
            }
        }
        if let Some(d) = &pass.depth {
            match self.resource(&d.target) {
                Some(r)
                    if r.kind == ResourceKind::Texture
                        && r.format == Some(TexelFormat::Depth32Float) => {}
                _ => p.push(format!(
                    "{at}: depth target `{}` must be a depth32float texture resource",
                    d.target
                )),
            }
        }
    }

    fn check_binding(
        &self,
        info: &crate::manifest::ResourceInfo,
        target: &str,
        at: &str,
        p: &mut Vec<String>,
    ) {
        let (name, previous) = match target.strip_suffix(PREVIOUS) {
            Some(n) => (n, true),
            None => (target, false),
        };
        let Some(r) = self.resource(name) else {
            p.push(format!(
                "{at}: binds `{}` to `{target}`, which is not a resource",
                info.name
            ));
            return;
        };
        let wrong = |what: &str| {
            format!(
                "{at}: `{}` is a {what} in the WGSL, but `{name}` is a {:?} resource",
                info.name, r.kind
            )
        };
        if previous && r.lifetime != Lifetime::History {
            p.push(format!(
                "{at}: `{target}`: only history resources have a `{PREVIOUS}` half"
            ));
        }
        match info.kind {
            BindingKind::UniformBuffer if r.kind != ResourceKind::Uniform => {
                p.push(wrong("uniform buffer"))
            }
            BindingKind::StorageBuffer if r.kind != ResourceKind::Counters => {
                p.push(wrong("storage buffer"))
            }
            BindingKind::Sampler if r.kind != ResourceKind::Sampler => p.push(wrong("sampler")),
            BindingKind::SampledTexture | BindingKind::StorageTexture => {
                if r.kind != ResourceKind::Texture {
                    p.push(wrong("texture"));
                    return;
                }
                let dim = r.dimension.unwrap_or(Dimension::D2);
                if info.dimension != Some(dim) {
                    p.push(format!(
                        "{at}: `{}` is a {:?} texture in the WGSL, `{name}` is {dim:?}",
                        info.name, info.dimension
                    ));
                }
                if info.kind == BindingKind::StorageTexture {
                    if info.format.as_deref() != r.format.map(TexelFormat::wgsl) {
                        p.push(format!(
                            "{at}: `{}` stores {:?} texels, but `{name}` is {:?}",
                            info.name, info.format, r.format
                        ));
                    }
                    if info.access.is_some_and(Access::writes) && (previous || r.upload.is_some()) {
                        p.push(format!(
                            "{at}: `{}` writes `{target}`, which only passes may read (uploaded, or last frame's)",
                            info.name
                        ));
                    }
                }
            }
            BindingKind::Other => p.push(format!(
                "{at}: `{}` has a type no backend can bind",
                info.name
            )),
            _ => {}
        }
    }
}

fn check_resource(r: &ResourceDesc, at: &str, p: &mut Vec<String>) {
    if let Some(u) = &r.upload
        && !UPLOADS.contains(&u.as_str())
    {
        p.push(format!(
            "{at}: uploads `{u}`; the host provides {UPLOADS:?}"
        ));
    }
    match r.kind {
        ResourceKind::Texture => {
            if r.format.is_none() {
                p.push(format!("{at}: a texture needs a `format`"));
            }
            if r.upload.is_some() && r.extent.is_some() {
                p.push(format!(
                    "{at}: an uploaded texture takes its data's size; drop `extent`"
                ));
            }
            if let Some(e) = &r.extent
                && let Err(e) = e.resolve(1, 1)
            {
                p.push(format!("{at}: {e}"));
            }
            if r.upload.is_some() && r.lifetime != Lifetime::Persistent {
                p.push(format!("{at}: an uploaded texture is `persistent`"));
            }
            if r.external && r.dimension.unwrap_or(Dimension::D2) != Dimension::D2 {
                p.push(format!("{at}: an external texture is 2d"));
            }
        }
        ResourceKind::Uniform if r.upload.as_deref() != Some("frame") => {
            p.push(format!("{at}: the uniform block is uploaded from `frame`"))
        }
        ResourceKind::Counters if r.counters.is_empty() => {
            p.push(format!("{at}: a counters buffer lists its `counters`"))
        }
        _ => {}
    }
    if r.kind != ResourceKind::Texture
        && (r.format.is_some() || r.extent.is_some() || r.dimension.is_some() || r.external)
    {
        p.push(format!(
            "{at}: only textures have a format, extent, dimension or external target"
        ));
    }
    if r.kind != ResourceKind::Sampler && (r.filter.is_some() || r.address.is_some()) {
        p.push(format!("{at}: only samplers have `filter` and `address`"));
    }
    if r.lifetime == Lifetime::History && r.kind != ResourceKind::Texture {
        p.push(format!("{at}: only textures can be history"));
    }
    let computed_persistent = r.lifetime == Lifetime::Persistent && r.upload.is_none();
    if !r.inputs.is_empty() && !computed_persistent {
        p.push(format!(
            "{at}: only a computed persistent resource has `inputs` (the others are made every frame or uploaded)"
        ));
    }
    for input in &r.inputs {
        if input_bytes(input).is_none() {
            p.push(format!(
                "{at}: input `{input}` is no member of the uniform block `Frame`, nor a \
                 component of one (`member.x` to `member.w`)"
            ));
        }
    }
    for (input, tolerance) in &r.tolerance {
        if !r.inputs.contains(input) {
            p.push(format!(
                "{at}: `tolerance` names `{input}`, which is not one of its `inputs`"
            ));
        } else if !crate::desc::input_is_float(input) {
            p.push(format!(
                "{at}: `tolerance` names `{input}`, which is not made of f32 values"
            ));
        }
        if !(tolerance.is_finite() && *tolerance > 0.0) {
            p.push(format!(
                "{at}: the tolerance of `{input}` is {tolerance}: it must be a finite number > 0"
            ));
        }
    }
}
