// A float assigned to an integer binding.
@compute @workgroup_size(1)
fn main() {
    let count: u32 = 1.5;
}
