//! Times one harness over the files of a folder (a corpus): the failing inputs with their
//! violations, the total, the executions per second, and the slowest inputs.
//!
//! ```text
//! cargo run --release --no-default-features --example time_target -- pipeline corpus/pipeline
//! ```

use std::time::Instant;

fn main() {
    let mut args = std::env::args().skip(1);
    let (Some(name), Some(dir)) = (args.next(), args.next()) else {
        eprintln!("usage: time_target TARGET FOLDER");
        std::process::exit(2);
    };
    let Some(target) = strak_fuzz::TARGETS.iter().find(|t| t.name == name) else {
        eprintln!("no target `{name}`");
        std::process::exit(2);
    };
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("read the folder")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_file())
        .collect();
    files.sort();
    let mut times = Vec::new();
    let start = Instant::now();
    let mut failures = 0;
    for f in &files {
        let bytes = std::fs::read(f).expect("read an input");
        let t = Instant::now();
        if let Err(v) = (target.run)(&bytes) {
            failures += 1;
            println!("failing: {}\n  {v}", f.display());
        }
        times.push((t.elapsed().as_secs_f64(), f.clone()));
    }
    let total = start.elapsed().as_secs_f64();
    #[allow(clippy::cast_precision_loss)]
    let rate = files.len() as f64 / total;
    println!(
        "{} inputs in {total:.3} s: {rate:.0} executions/s, {failures} failing",
        files.len()
    );
    times.sort_by(|a, b| b.0.total_cmp(&a.0));
    for (t, f) in times.iter().take(10) {
        println!("{:8.2} ms  {}", t * 1e3, f.display());
    }
}
