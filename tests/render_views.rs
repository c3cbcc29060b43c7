//! `scripts/render_views.py` (ParaView's pvbatch in an Xvfb display) on three shipped cases of different
//! shapes: the tutorial's axisymmetric sphere on a Lennard-Jones flat, the 3D double cantilever
//! beam on its cohesive ligament, and the 3D blocks joined by cohesive elements. Each run's views
//! are written, their colour bars name the quantity and the case's unit, and the von Mises view
//! is zoomed on the body's contact region (the body fills a good share of the image, with more
//! than a handful of colours) rather than showing a fixed window beside it.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Runs `case` (with `sets`) into a fresh folder and renders its views; returns (folder, the
/// renderer's standard output).
fn render(name: &str, case: &str, sets: &[&str]) -> (PathBuf, String) {
    let out = root().join("target").join("test-out").join("render-views").join(name);
    let _ = std::fs::remove_dir_all(&out);
    let mut run = Command::new(env!("CARGO_BIN_EXE_stiction"));
    run.current_dir(root()).args(["run", case, "--quiet", "--out"]).arg(&out);
    for set in sets {
        run.args(["--set", set]);
    }
    let ran = run.output().unwrap();
    assert!(ran.status.success(), "{case}: {}", String::from_utf8_lossy(&ran.stderr));
    let display = Xvfb::start();
    let rendered = Command::new("pvbatch")
        .current_dir(root())
        .env("DISPLAY", &display.name)
        .arg("scripts/render_views.py")
        .arg(&out)
        .output()
        .expect("pvbatch (Debian's paraview) must be installed: scripts/ensure-paraview.sh");
    drop(display);
    let stdout = String::from_utf8_lossy(&rendered.stdout).to_string();
    assert!(
        rendered.status.success(),
        "render_views.py failed on {case}: {stdout}\n{}",
        String::from_utf8_lossy(&rendered.stderr)
    );
    (out, stdout)
}

/// An X server of its own for pvbatch: Xvfb picks a free display and writes its number once it
/// accepts connections (`-displayfd`), so there is no race between starting it and using it.
struct Xvfb {
    child: std::process::Child,
    name: String,
}

impl Xvfb {
    fn start() -> Self {
        use std::io::BufRead;
        let mut child = Command::new("Xvfb")
            // -noreset: by default the server resets when its last client disconnects, and
            // pvbatch, which connects more than once, then fails now and then ("bad X server
            // connection")
            .args(["-displayfd", "1", "-screen", "0", "1600x1200x24", "-nolisten", "tcp", "-noreset"])
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::null())
            .spawn()
            .expect("Xvfb (Debian's xvfb) must be installed: scripts/ensure-paraview.sh");
        let mut line = String::new();
        std::io::BufReader::new(child.stdout.take().unwrap()).read_line(&mut line).unwrap();
        let number: u32 = line.trim().parse().unwrap_or_else(|_| panic!("Xvfb gave no display: '{line}'"));
        Xvfb { child, name: format!(":{number}") }
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        // SIGTERM, so that Xvfb removes its lock file and socket
        let _ = Command::new("kill").arg(self.child.id().to_string()).status();
        let _ = self.child.wait();
    }
}

/// (share of the pixels that are not the white background, number of distinct colours).
fn coverage(png_file: &Path) -> (f64, usize) {
    let decoder = png::Decoder::new(std::fs::File::open(png_file).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    let channels = info.color_type.samples();
    let pixels: Vec<&[u8]> = buf[..info.buffer_size()].chunks(channels).collect();
    let drawn = pixels.iter().filter(|p| p[..3].iter().any(|&c| c < 250)).count();
    let colours: std::collections::HashSet<[u8; 3]> = pixels.iter().map(|p| [p[0], p[1], p[2]]).collect();
    (drawn as f64 / pixels.len() as f64, colours.len())
}

fn check_views(out: &Path, stdout: &str, views: &[&str], bars: &[&str]) {
    for view in views {
        let file = out.join(format!("view_{view}.png"));
        assert!(file.exists() && stdout.contains(&format!("view_{view}.png")), "no {}: {stdout}", file.display());
    }
    for bar in bars {
        assert!(stdout.contains(bar), "no colour bar '{bar}': {stdout}");
    }
    let (drawn, colours) = coverage(&out.join("view_von_mises.png"));
    assert!(drawn > 0.2, "{}: the body covers {:.0}% of the von Mises view", out.display(), 100.0 * drawn);
    assert!(colours > 50, "{}: {colours} colours in the von Mises view", out.display());
    assert!(out.join("contact_views.pvsm").exists());
    println!("{}: body on {:.0}% of the von Mises view, {colours} colours", out.display(), 100.0 * drawn);
}

#[test]
fn render_views_works_on_an_axisymmetric_sphere_a_3d_beam_and_3d_blocks_with_units() {
    let (out, stdout) = render("sphere", "docs/tutorial/sphere.toml", &[]);
    check_views(&out, &stdout, &["von_mises", "contact"], &["von Mises stress (GPa)", "normal traction (GPa)"]);
    // the beam until its crack grows (t = 0.38 is the largest tensile force)
    let (out, stdout) = render("dcb", "cases/validation/dcb.toml", &["steps.0.end_time=0.4"]);
    check_views(&out, &stdout, &["von_mises", "contact"], &["von Mises stress (case units)", "normal traction"]);
    let (out, stdout) = render("blocks", "cases/validation/two-blocks-cohesive.toml", &[]);
    check_views(&out, &stdout, &["von_mises", "contact"], &["von Mises stress (case units)"]);
}
