// `densty` is misspelt.
fn density(h: f32) -> f32 {
    return clamp(h, 0.0, 1.0);
}

@compute @workgroup_size(1)
fn main() {
    let d = densty(0.5);
}
