fn main() {
    println!("mintorque");
}
