//! Temporary entry point of the `otg` branch: only `shearcut trajectory --cases FILE [--out FILE]`.
//! The lead replaces this with the clap CLI; all logic lives in `shearcut::trajectory_cases`.

use std::io::Write;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = "usage: shearcut trajectory --cases FILE.jsonl [--out FILE]";
    if args.first().map(String::as_str) != Some("trajectory") {
        eprintln!("{usage}");
        return ExitCode::from(2);
    }
    let (mut cases, mut out) = (None, None);
    let mut it = args[1..].iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--cases" => cases = it.next().cloned(),
            "--out" => out = it.next().cloned(),
            _ => {
                eprintln!("unknown argument {a}\n{usage}");
                return ExitCode::from(2);
            }
        }
    }
    let Some(cases) = cases else {
        eprintln!("{usage}");
        return ExitCode::from(2);
    };
    let mut sink: Box<dyn Write> = match out {
        Some(path) => match std::fs::File::create(&path) {
            Ok(f) => Box::new(std::io::BufWriter::new(f)),
            Err(e) => {
                eprintln!("cannot create {path}: {e}");
                return ExitCode::from(2);
            }
        },
        None => Box::new(std::io::BufWriter::new(std::io::stdout().lock())),
    };
    match shearcut::trajectory_cases::run_cases(std::path::Path::new(&cases), &mut *sink) {
        Ok(r) => {
            let _ = sink.flush();
            eprintln!("{} cases: {} ok, {} errors", r.cases, r.ok, r.errors);
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("cannot run cases from {cases}: {e}");
            ExitCode::from(2)
        }
    }
}
