//! `stratus export-kit` as an integrator meets it: every file the kit's README promises, with
//! contents that could be wrong (sizes, magic numbers, the plan of the golden).

use std::{path::Path, process::Command};

#[test]
fn the_kit_holds_what_its_readme_promises() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("kit");
    let _ = std::fs::remove_dir_all(&dir);
    let out = Command::new(env!("CARGO_BIN_EXE_stratus"))
        .args([
            "export-kit",
            "--scenes",
            "cumulus-noon",
            "--size",
            "32x18",
            "--out",
        ])
        .arg(&dir)
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("running stratus");
    assert!(
        out.status.success(),
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    let read = |p: &str| std::fs::read(dir.join(p)).unwrap_or_else(|e| panic!("{p}: {e}"));
    let json = |p: &str| -> serde_json::Value {
        serde_json::from_slice(&read(p)).unwrap_or_else(|e| panic!("{p}: {e}"))
    };

    let kit = json("kit.json");
    assert_eq!(kit["kit_version"], 1);
    let golden = &kit["goldens"][0];
    assert_eq!(golden["name"], "cumulus-noon");
    assert_eq!(golden["size"], serde_json::json!([32, 18]));

    // The uniform block: every member of the one declaration in its bytes, as the header and
    // the JSON say (counted from the declaration, so a new member needs no edit here).
    let bytes = std::mem::size_of::<stratus_scene::FrameUniforms>();
    let members = stratus_scene::FrameUniforms::MEMBERS.len();
    assert_eq!(read(golden["uniforms"].as_str().unwrap()).len(), bytes);
    let header = String::from_utf8(read("uniforms.h")).unwrap();
    assert!(
        header.contains("float camera_position[3];")
            && header.contains("float tan_half_fov;")
            && header.contains("uint32_t size[2];")
            && header.contains("float anvil_shear[2];")
            && header.contains(&format!("{members} members"))
            && header.contains(&format!("== {bytes}")),
        "{header}"
    );
    let listed = json("uniforms.json")["members"].as_array().unwrap().clone();
    assert_eq!(listed.len(), members);
    let downward = listed.iter().find(|m| m["name"] == "downward_dimming");
    assert_eq!(
        downward.map(|m| (&m["type"], &m["size"])),
        Some((&"f32".into(), &4.into()))
    );

    // The header compiles as C11, and its static assertions (the size and every member's
    // offset) hold under the C compiler's own layout rules, the ones an engine's C or C++
    // code uses. `cc` is the compiler Rust links with, so it is there wherever this runs.
    let c = dir.join("uniforms_check.c");
    std::fs::write(
        &c,
        "#include \"uniforms.h\"\nint main(void) { return 0; }\n",
    )
    .unwrap();
    let cc = Command::new("cc")
        .args(["-std=c11", "-Wall", "-Werror", "-fsyntax-only"])
        .arg(&c)
        .current_dir(&dir)
        .output()
        .expect("running cc");
    assert!(
        cc.status.success(),
        "uniforms.h does not compile: {}",
        String::from_utf8_lossy(&cc.stderr)
    );

    // The plan: the march and the composite (skipped when the host draws the HDR output),
    // dispatched over the golden's size, then the passes only a host asks for: present and
    // HDR (composed, then drawn into its target), the shadow map for its geometry.
    let plan = json(golden["plan"].as_str().unwrap());
    let passes: Vec<&str> = plan["passes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        passes,
        [
            "march",
            "composite",
            "present",
            "hdr-composite",
            "hdr",
            "host-shadow"
        ]
    );
    assert_eq!(plan["passes"][2]["when"], "present");
    assert_eq!(plan["passes"][3]["when"], "hdr");
    assert_eq!(plan["passes"][4]["when"], "hdr");
    assert_eq!(plan["passes"][5]["when"], "shadow");
    assert_eq!(plan["passes"][1]["when"], "!hdr");
    assert_eq!(plan["passes"][0]["dispatch"], serde_json::json!([4, 3, 1]));
    assert_eq!(plan["passes"][0]["overrides"]["DETAIL"], 1.0);

    // The image, the WGSL, the translations and the manifest with the graph.
    let png = image::open(dir.join(golden["image"].as_str().unwrap())).unwrap();
    assert_eq!((png.width(), png.height()), (32, 18));
    assert!(
        String::from_utf8(read("wgsl/clouds.wgsl"))
            .unwrap()
            .contains("fn march(")
    );
    assert!(read("shaders/clouds.full.spv").starts_with(&[0x03, 0x02, 0x23, 0x07]));
    assert!(json("manifest.json")["graph"]["pass"].is_array());
    let readme = String::from_utf8(read("README.md")).unwrap();
    assert!(readme.contains("Running a frame"));
    assert!(
        readme.contains(&format!("({members} named members, {bytes} bytes;"))
            && !readme.contains("{BYTES}"),
        "the README's uniform numbers"
    );

    // The tower golden: the first scene with the host's depth, its uniforms saying so.
    let tower = &kit["goldens"][1];
    assert_eq!(tower["name"], "cumulus-noon-tower");
    assert!(golden["scene_depth"].is_null());
    let depth: Vec<f32> = read(tower["scene_depth"].as_str().unwrap())
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
        .collect();
    assert_eq!(depth.len(), 32 * 18);
    let covered = depth.iter().filter(|&&d| d > 0.0).count();
    assert!(
        covered > 0 && covered < depth.len(),
        "the tower covers {covered} of {} pixels",
        depth.len()
    );
    let block = read(tower["uniforms"].as_str().unwrap());
    let word = |name: &str| {
        let m = listed.iter().find(|m| m["name"] == name).unwrap();
        let o = m["offset"].as_u64().unwrap() as usize;
        u32::from_le_bytes(block[o..o + 4].try_into().unwrap())
    };
    assert_eq!(word("flags") & 128, 128, "FLAG_SCENE_DEPTH");
    assert_eq!(f32::from_bits(word("scene_depth_b")), 0.1);

    // Noise: DDS (magic, and a volume's depth) and raw bytes of the same size.
    let set = kit["noise"][0]["textures"]["noise.shape"].clone();
    let dds = read(set["dds"].as_str().unwrap());
    let raw = read(set["raw"].as_str().unwrap());
    assert_eq!(&dds[..4], b"DDS ");
    let size: Vec<u64> = set["size"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_u64().unwrap())
        .collect();
    assert_eq!(raw.len() as u64, size.iter().product::<u64>() * 4);
    let depth = u32::from_le_bytes(dds[24..28].try_into().unwrap());
    assert_eq!(u64::from(depth), size[2]);
    assert!(dds.ends_with(&raw), "the DDS holds the raw texels");
}
