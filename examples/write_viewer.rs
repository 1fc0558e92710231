//! (Re)writes `motion.html`, `filmstrip.svg` and `filmstrip.png` in each plan directory given, until the
//! CLI's `mintorque view DIR` does it:
//!
//!     cargo run --release --example write_viewer -- out/pendulum [more plan dirs…]

use std::process::ExitCode;

fn main() -> ExitCode {
    let dirs: Vec<String> = std::env::args().skip(1).collect();
    if dirs.is_empty() {
        eprintln!("usage: write_viewer PLAN_DIR...");
        return ExitCode::from(2);
    }
    for dir in &dirs {
        let dir = std::path::Path::new(dir);
        if let Err(e) = mintorque::report::viewer::write_view_files(dir) {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
        println!("{}", dir.join("motion.html").display());
    }
    ExitCode::SUCCESS
}
