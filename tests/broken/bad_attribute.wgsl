// `@workgroup` is not an attribute (`@workgroup_size` is).
@compute @workgroup(8, 8, 1)
fn main() {
}
