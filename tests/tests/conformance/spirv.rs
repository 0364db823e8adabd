//! naga's GLSL and HLSL, translated at test time from the embedded WGSL (`spirv-out/` keeps
//! only the SPIR-V), compiled to SPIR-V by glslangValidator, and the descriptor slots the ash
//! backend binds for them (read from what glslang declared).

use std::{
    collections::BTreeMap,
    path::{Path, PathBuf},
    process::Command,
    sync::OnceLock,
};

use stratus_backend_ash::{PassShader, Slot, SlotContent};
use stratus_graph::{
    FramePlan, Program,
    desc::ResourceKind,
    manifest::BindingKind,
    plan::{Pass, PassKind},
};

/// The entry point of a compute pass (supplied modules replace compute passes only).
fn compute_entry(pass: &Pass) -> Option<&str> {
    match &pass.kind {
        PassKind::Compute { entry, .. } => Some(entry),
        PassKind::Raster { .. } => None,
    }
}

/// The name of the resource a binding binds.
fn bound(plan: &FramePlan, b: &stratus_graph::plan::Binding) -> String {
    stratus_graph::plan::bound_name(plan, b)
}

/// Which of naga's texts a module was compiled from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Lang {
    /// `<module>.<variant>.<entry>.comp.glsl`, `glslangValidator -V -S comp`.
    Glsl,
    /// `<module>.<variant>.hlsl`, `glslangValidator -D -V -e <entry> -S comp`, then
    /// `spirv-opt --legalize-hlsl`.
    Hlsl,
}

/// A descriptor glslang declared: the variable's name (if any) and its decorations.
#[derive(Clone, Debug, PartialEq)]
pub struct Declared {
    pub name: String,
    pub set: u32,
    pub binding: u32,
}

/// What the SPIR-V says about its interface: entry point names and every descriptor.
#[derive(Debug, Default)]
pub struct Reflection {
    pub entry_points: Vec<String>,
    pub descriptors: Vec<Declared>,
}

const OP_ENTRY_POINT: u32 = 15;
const OP_NAME: u32 = 5;
const OP_DECORATE: u32 = 71;
const DECORATION_BINDING: u32 = 33;
const DECORATION_DESCRIPTOR_SET: u32 = 34;

/// A SPIR-V literal string starting at `words[0]`.
fn string(words: &[u32]) -> String {
    let bytes: Vec<u8> = words
        .iter()
        .flat_map(|w| w.to_le_bytes())
        .take_while(|&b| b != 0)
        .collect();
    String::from_utf8_lossy(&bytes).into_owned()
}

/// Reads the entry points, names and `DescriptorSet`/`Binding` decorations of a module.
pub fn reflect(words: &[u32]) -> Result<Reflection, String> {
    if words.len() < 5 || words[0] != 0x0723_0203 {
        return Err("not SPIR-V (no magic number)".into());
    }
    let mut names: BTreeMap<u32, String> = BTreeMap::new();
    let mut sets: BTreeMap<u32, u32> = BTreeMap::new();
    let mut bindings: BTreeMap<u32, u32> = BTreeMap::new();
    let mut out = Reflection::default();
    let mut i = 5;
    while i < words.len() {
        let (op, len) = (words[i] & 0xffff, (words[i] >> 16) as usize);
        if len == 0 || i + len > words.len() {
            return Err(format!("malformed instruction at word {i}"));
        }
        let args = &words[i + 1..i + len];
        match op {
            OP_ENTRY_POINT if args.len() >= 3 => out.entry_points.push(string(&args[2..])),
            OP_NAME if args.len() >= 2 => {
                names.insert(args[0], string(&args[1..]));
            }
            OP_DECORATE if args.len() >= 3 => match args[1] {
                DECORATION_DESCRIPTOR_SET => {
                    sets.insert(args[0], args[2]);
                }
                DECORATION_BINDING => {
                    bindings.insert(args[0], args[2]);
                }
                _ => {}
            },
            _ => {}
        }
        i += len;
    }
    for (id, binding) in bindings {
        out.descriptors.push(Declared {
            name: names.get(&id).cloned().unwrap_or_default(),
            set: sets.get(&id).copied().unwrap_or(0),
            binding,
        });
    }
    Ok(out)
}

/// Every variant's GLSL, HLSL and MSL, translated once per run from the embedded WGSL, which
/// `spirv_out_is_fresh` holds to the committed SPIR-V: file name (as the manifest names it)
/// -> text.
pub fn translations() -> Result<&'static BTreeMap<String, Vec<u8>>, String> {
    static ALL: OnceLock<Result<BTreeMap<String, Vec<u8>>, String>> = OnceLock::new();
    ALL.get_or_init(|| {
        let tree = stratus_shaders::ShaderTree::embedded().map_err(|e| e.to_string())?;
        stratus_shaders::build_outputs(&tree, stratus_shaders::Languages::All)
            .map_err(|e| e.to_string())
    })
    .as_ref()
    .map_err(Clone::clone)
}

/// The translation `name` as a file under `scratch` (glslang reads files), written once and
/// renamed into place so that concurrent tests never read half of it.
fn translation_file(name: &str, scratch: &Path) -> Result<PathBuf, String> {
    let bytes = translations()?
        .get(name)
        .ok_or_else(|| format!("naga wrote no {name}"))?;
    let dir = scratch.join("translations");
    let path = dir.join(name);
    if std::fs::read(&path).is_ok_and(|b| &b == bytes) {
        return Ok(path);
    }
    std::fs::create_dir_all(&dir).map_err(|e| format!("creating {}: {e}", dir.display()))?;
    let tmp = dir.join(format!(
        "{name}.{}.{:?}.tmp",
        std::process::id(),
        std::thread::current().id()
    ));
    std::fs::write(&tmp, bytes).map_err(|e| format!("writing {}: {e}", tmp.display()))?;
    std::fs::rename(&tmp, &path).map_err(|e| format!("renaming to {}: {e}", path.display()))?;
    Ok(path)
}

/// Runs `tool args... -o out source`, failing with its output.
fn run_tool(
    tool: &str,
    package: &str,
    args: &[&str],
    source: &Path,
    out: &Path,
) -> Result<(), String> {
    let output = Command::new(tool)
        .args(args)
        .arg("-o")
        .arg(out)
        .arg(source)
        .output()
        .map_err(|e| {
            format!("could not run {tool} ({e}); install it with `apt-get install {package}`")
        })?;
    if !output.status.success() {
        return Err(format!(
            "{tool} {} -o {} {} failed:\n{}{}",
            args.join(" "),
            out.display(),
            source.display(),
            String::from_utf8_lossy(&output.stdout),
            String::from_utf8_lossy(&output.stderr)
        ));
    }
    Ok(())
}

/// Runs glslangValidator and reads the SPIR-V it wrote. With `legalize` the output first goes
/// through `spirv-opt --legalize-hlsl`: glslang's HLSL front end keeps naga's
/// `static const SamplerState noise_sampler = nagaSamplerHeap[...]` as a sampler stored in a
/// Private variable, which is what HLSL legalization exists to remove (Debian's glslang is
/// built without the optimizer that would run it, even with `-Os`). spirv-val accepts the
/// unlegalized module; lavapipe's compiler crashes on it (SIGSEGV in
/// vkCreateComputePipelines).
fn glslang(args: &[&str], source: &Path, out: &Path, legalize: bool) -> Result<Vec<u32>, String> {
    run_tool("glslangValidator", "glslang-tools", args, source, out)?;
    if legalize {
        run_tool("spirv-opt", "spirv-tools", &["--legalize-hlsl"], out, out)?;
    }
    let val = Command::new("spirv-val")
        .args(["--target-env", "vulkan1.1"])
        .arg(out)
        .output()
        .map_err(|e| {
            format!("could not run spirv-val ({e}); install it with `apt-get install spirv-tools`")
        })?;
    if !val.status.success() {
        return Err(format!(
            "spirv-val --target-env vulkan1.1 {} (from {}) failed:\n{}{}",
            out.display(),
            source.display(),
            String::from_utf8_lossy(&val.stdout),
            String::from_utf8_lossy(&val.stderr)
        ));
    }
    let bytes = std::fs::read(out).map_err(|e| format!("reading {}: {e}", out.display()))?;
    if bytes.len() % 4 != 0 {
        return Err(format!("{}: not a whole number of words", out.display()));
    }
    Ok(bytes
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect())
}

/// The committed module of compute pass `pass`, bound as the plan says (what
/// `Renderer::render` runs), as a supplied module.
pub fn committed(plan: &FramePlan, pass: &Pass) -> Result<PassShader, String> {
    let program = Program::embedded().map_err(|e| e.to_string())?;
    PassShader::from_program(&program, plan, pass).map_err(|e| e.to_string())
}

/// Compiles naga's `lang` text of the plan's variant for every compute pass, and lists the
/// slots of each module. `scratch` receives the `.spv` files.
pub fn compile(plan: &FramePlan, lang: Lang, scratch: &Path) -> Result<Vec<PassShader>, String> {
    let program = Program::embedded().map_err(|e| e.to_string())?;
    std::fs::create_dir_all(scratch).map_err(|e| e.to_string())?;
    let mut shaders = Vec::new();
    for pass in &plan.passes {
        let Some(entry_point) = compute_entry(pass) else {
            continue;
        };
        let chosen = &plan.modules[&pass.module].variant;
        let variant = program
            .manifest
            .module(&pass.module)
            .and_then(|m| m.variants.iter().find(|v| &v.name == chosen))
            .ok_or_else(|| format!("the manifest has no variant {}.{chosen}", pass.module))?;
        let out = scratch.join(format!(
            "{}.{chosen}.{entry_point}.{lang:?}.spv",
            pass.module
        ));
        let (words, slots, entry) = match lang {
            Lang::Glsl => {
                let file = variant
                    .files
                    .glsl
                    .get(entry_point)
                    .ok_or_else(|| format!("no GLSL for entry point {entry_point}"))?;
                let source = translation_file(file, scratch)?;
                let words = glslang(&["-V", "-S", "comp"], &source, &out, false)?;
                let r = reflect(&words)?;
                (words, glsl_slots(plan, pass, &r)?, entry_of(&r, &["main"])?)
            }
            Lang::Hlsl => {
                let file = translation_file(&variant.files.hlsl, scratch)?;
                let text = std::fs::read_to_string(&file)
                    .map_err(|e| format!("reading {}: {e}", file.display()))?;
                let words = glslang(
                    &["-D", "-V", "-e", entry_point, "-S", "comp"],
                    &file,
                    &out,
                    true,
                )?;
                let r = reflect(&words)?;
                let entry = entry_of(&r, &[entry_point, "main"])?;
                (words, hlsl_slots(plan, pass, &text, &r)?, entry)
            }
        };
        shaders.push(PassShader {
            spirv: words,
            entry,
            slots,
        });
    }
    Ok(shaders)
}

/// The entry point glslang wrote: the first of `candidates` the module has.
fn entry_of(r: &Reflection, candidates: &[&str]) -> Result<String, String> {
    candidates
        .iter()
        .find(|c| r.entry_points.iter().any(|e| e == *c))
        .map(|c| c.to_string())
        .ok_or_else(|| {
            format!(
                "glslang wrote entry points {:?}, none of {candidates:?}",
                r.entry_points
            )
        })
}

/// Maps every descriptor glslang declared to a slot with `lookup`, or fails naming it.
fn slots_for(
    pass: &Pass,
    r: &Reflection,
    lookup: impl Fn(&Declared) -> Option<SlotContent>,
) -> Result<Vec<Slot>, String> {
    r.descriptors
        .iter()
        .map(|d| {
            let content = lookup(d).ok_or_else(|| {
                format!(
                    "pass `{}`: glslang declared `{}` at set {} binding {}, which nothing in the frame stands for",
                    pass.name, d.name, d.set, d.binding
                )
            })?;
            Ok(Slot {
                set: d.set,
                binding: d.binding,
                content,
            })
        })
        .collect()
}

/// The GLSL's bindings per group (translate.rs).
const PER_GROUP: u32 = stratus_shaders::translate::BINDINGS_PER_GROUP;

/// naga's GLSL: every binding at `group * BINDINGS_PER_GROUP + binding` in set 0 (translate.rs), sampled
/// textures combined with the sampler (GLSL has no separate sampler objects; naga drops the
/// sampler binding). The names naga gives (`_group_G_binding_B_cs`) are checked against this.
fn glsl_slots(plan: &FramePlan, pass: &Pass, r: &Reflection) -> Result<Vec<Slot>, String> {
    for d in &r.descriptors {
        let parsed = d
            .name
            .strip_prefix("_group_")
            .and_then(|s| s.strip_suffix("_cs"))
            .and_then(|s| s.split_once("_binding_"))
            .and_then(|(g, b)| Some((g.parse::<u32>().ok()?, b.parse::<u32>().ok()?)));
        match parsed {
            Some((g, b)) if (d.set, d.binding) != (0, g * PER_GROUP + b) => {
                return Err(format!(
                    "`{}` is at set {} binding {}, not at binding {} (group * BINDINGS_PER_GROUP + binding)",
                    d.name,
                    d.set,
                    d.binding,
                    g * PER_GROUP + b
                ));
            }
            _ => {}
        }
    }
    slots_for(pass, r, |d| {
        let b = pass
            .bindings
            .iter()
            .find(|b| d.set == 0 && b.group * PER_GROUP + b.binding == d.binding)?;
        Some(if b.info.kind == BindingKind::SampledTexture {
            SlotContent::CombinedWithSampler(bound(plan, b))
        } else {
            SlotContent::Plan(bound(plan, b))
        })
    })
}

/// `register(<class><n>, space<m>)` of the HLSL declaration of `name`, e.g. `("s", 32, 0)`.
fn hlsl_register(text: &str, name: &str) -> Option<(String, u32, u32)> {
    let line = text.lines().find(|l| {
        l.split(|c: char| !(c.is_alphanumeric() || c == '_'))
            .any(|w| w == name)
            && l.contains("register(")
    })?;
    let inside = line.split_once("register(")?.1.split_once(')')?.0;
    let (reg, space) = match inside.split_once(',') {
        Some((r, s)) => (r.trim(), s.trim().strip_prefix("space")?.parse().ok()?),
        None => (inside.trim(), 0),
    };
    let class: String = reg.chars().take_while(|c| c.is_alphabetic()).collect();
    let n = reg[class.len()..].parse().ok()?;
    Some((class, n, space))
}

/// naga's HLSL: `@group` = space = set and `@binding` = register = binding (naga's and
/// glslang's default mappings), except samplers: they are read from the sampler heap
/// (`nagaSamplerHeap`, an array of samplers) at the index that the group's index buffer
/// (`nagaGroup<G>SamplerIndexArray`) holds for the sampler's binding. Both are bound where
/// the HLSL declares them: the heap filled with the noise sampler, the index buffer with
/// zeros. (naga's own HLSL options put them at `s0, space0` and `t0, space255`, which glslang
/// cannot bind: see `hlsl_options` in crates/shaders/src/translate.rs.)
fn hlsl_slots(
    plan: &FramePlan,
    pass: &Pass,
    text: &str,
    r: &Reflection,
) -> Result<Vec<Slot>, String> {
    let heap_size = text
        .split_once("nagaSamplerHeap[")
        .and_then(|(_, rest)| rest.split_once(']'))
        .and_then(|(n, _)| n.parse::<u32>().ok());
    slots_for(pass, r, |d| {
        if d.name == "nagaSamplerHeap" {
            let (class, reg, space) = hlsl_register(text, &d.name)?;
            return ((class.as_str(), reg, space) == ("s", d.binding, d.set))
                .then_some(SlotContent::SamplerArray(heap_size?));
        }
        if let Some(group) = d
            .name
            .strip_prefix("nagaGroup")
            .and_then(|s| s.strip_suffix("SamplerIndexArray"))
            .and_then(|g| g.parse::<u32>().ok())
        {
            let (class, reg, space) = hlsl_register(text, &d.name)?;
            // One index per binding number of the group.
            let words = pass
                .bindings
                .iter()
                .filter(|b| b.group == group)
                .map(|b| b.binding + 1)
                .max()?;
            return ((class.as_str(), reg, space) == ("t", d.binding, d.set))
                .then_some(SlotContent::SamplerIndices(words));
        }
        let b = pass
            .bindings
            .iter()
            .find(|b| (b.group, b.binding) == (d.set, d.binding))?;
        (plan.resources[b.resource].kind != ResourceKind::Sampler)
            .then_some(SlotContent::Plan(bound(plan, b)))
    })
}
