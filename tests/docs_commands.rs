//! The commands the manual shows run, so the docs cannot rot. Every line of a ```` ```sh ````
//! block in README.md and docs/*.md is run as written, from the repository's root, with the
//! `stiction` under test first on the PATH and `out/` pointed at a scratch folder, and must
//! exit 0: `stiction ...` commands are run, `bash SCRIPT` lines are checked to exist and parse
//! (`bash -n`: the scripts are long runs, exercised elsewhere), `export` lines are the reader's
//! setup; a ```` ```text ```` synopsis line `stiction SUBCOMMAND ...` must name a subcommand
//! that exists (`--help` exits 0). A block a test cannot run (a cluster script, ParaView, a user's own plugin) is marked
//! ```` ```sh no-run ````. TOML blocks must parse; the tutorial's files are the ones README
//! shows, and README quotes the numbers the tutorial's run prints (within the run-to-run spread).

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The manual's pages: README and the top level of docs/ (design notes are records, not
/// instructions).
fn pages() -> Vec<PathBuf> {
    let mut pages = vec![root().join("README.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "md"))
        .collect();
    docs.sort();
    pages.extend(docs);
    pages
}

/// (info string, text) of every fenced block of a Markdown page.
fn blocks(text: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let mut open: Option<(String, String)> = None;
    for line in text.lines() {
        match (&mut open, line.strip_prefix("```")) {
            (None, Some(info)) => open = Some((info.trim().to_string(), String::new())),
            (Some(_), Some("")) => out.push(open.take().unwrap()),
            (Some((_, body)), _) => {
                body.push_str(line);
                body.push('\n');
            }
            (None, None) => {}
        }
    }
    out
}

/// A command line without its trailing `  # comment`.
fn command(line: &str) -> &str {
    match line.find(" #") {
        Some(i) => line[..i].trim_end(),
        None => line.trim_end(),
    }
}

fn run(line: &str, scratch: &Path) -> std::process::Output {
    let exe_dir = Path::new(env!("CARGO_BIN_EXE_stiction")).parent().unwrap().to_path_buf();
    let path = std::env::join_paths(
        std::iter::once(exe_dir).chain(std::env::split_paths(&std::env::var_os("PATH").unwrap_or_default())),
    )
    .unwrap();
    let line = line.replace(" out/", &format!(" {}/", scratch.display()));
    Command::new("bash").arg("-c").arg(&line).current_dir(root()).env("PATH", path).output().unwrap()
}

#[test]
fn every_command_the_manual_shows_runs() {
    let scratch = root().join("target").join("test-out").join("docs-commands");
    let _ = std::fs::remove_dir_all(&scratch);
    std::fs::create_dir_all(&scratch).unwrap();
    let mut failures = Vec::new();
    let mut ran = 0;
    for page in pages() {
        let text = std::fs::read_to_string(&page).unwrap();
        let name = page.strip_prefix(root()).unwrap().display().to_string();
        for (info, body) in blocks(&text) {
            if info == "toml" {
                if let Err(e) = body.parse::<toml::Table>() {
                    failures.push(format!("{name}: a TOML block does not parse: {e}\n{body}"));
                }
                continue;
            }
            if info == "text" {
                // a synopsis: its subcommand must exist (`stiction plugin check LAW` -> `--help`)
                for line in body.lines().map(command).filter(|l| l.starts_with("stiction ")) {
                    let words: Vec<&str> = line
                        .split_whitespace()
                        .take_while(|w| w.chars().all(|c| c.is_ascii_lowercase() || c == '-') && !w.starts_with('-'))
                        .collect();
                    let help = run(&format!("{} --help", words.join(" ")), &scratch);
                    ran += 1;
                    if !help.status.success() {
                        failures.push(format!("{name}: `{line}`: `{} --help` fails", words.join(" ")));
                    }
                }
                continue;
            }
            if info != "sh" {
                continue;
            }
            for line in body.lines().map(command).filter(|l| !l.is_empty() && !l.starts_with('#')) {
                let first = line.split_whitespace().next().unwrap();
                let checked = match first {
                    "export" => continue,
                    "bash" => {
                        let script = line.split_whitespace().nth(1).unwrap();
                        run(&format!("bash -n {script}"), &scratch)
                    }
                    "stiction" => run(line, &scratch),
                    other => {
                        failures.push(format!(
                            "{name}: `{line}`: `{other}` is not a command this test runs; mark the block `sh no-run`"
                        ));
                        continue;
                    }
                };
                ran += 1;
                if !checked.status.success() {
                    failures.push(format!(
                        "{name}: `{line}` exited with {:?}:\n{}",
                        checked.status.code(),
                        String::from_utf8_lossy(&checked.stderr)
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    assert!(ran >= 15, "only {ran} commands found in the manual");
}

/// README's tutorial: the files it shows are the ones in docs/tutorial/, its run prints the
/// numbers README quotes, and its pull-off lies between the JKR (1.5 pi w R) and DMT (2 pi w R)
/// limits, where Maugis's transition puts a sphere of Tabor parameter 0.59.
#[test]
fn the_readme_tutorial_is_the_shipped_one_and_pulls_off_between_jkr_and_dmt() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let tutorial = root().join("docs").join("tutorial");
    let case = std::fs::read_to_string(tutorial.join("sphere.toml")).unwrap();
    let shown: Vec<String> = blocks(&readme).into_iter().filter(|(i, _)| i == "toml").map(|(_, b)| b).collect();
    assert_eq!(shown, vec![case], "README's case block must be docs/tutorial/sphere.toml");
    let geo = std::fs::read_to_string(tutorial.join("sphere.geo")).unwrap();
    let excerpt = blocks(&readme).into_iter().find(|(_, b)| b.contains("DefineConstant")).expect("the .geo excerpt").1;
    for line in excerpt.lines().filter(|l| !l.starts_with("//") && *l != "...") {
        let code = line.split("//").next().unwrap().trim_end();
        assert!(geo.lines().any(|g| g.trim_end() == code), "README's .geo line `{code}` is not in sphere.geo");
    }

    let scratch = root().join("target").join("test-out").join("docs-tutorial");
    let _ = std::fs::remove_dir_all(&scratch);
    let out = run("stiction run docs/tutorial/sphere.toml --out out/tutorial --quiet", &scratch);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(scratch.join("tutorial").join("summary.json")).unwrap()).unwrap();
    let flat = &summary["interfaces"][0];
    // README quotes the closing line; the increments the quasi-Newton solver's measured costs
    // choose move the pull-off by a fraction of a percent from run to run
    let quote = readme.lines().find(|l| l.trim_start().starts_with("flat: max force")).expect("README's quoted line");
    let number_after = |key: &str| -> f64 {
        let rest = &quote[quote.find(key).unwrap() + key.len()..];
        rest.split_whitespace().next().unwrap().parse().unwrap()
    };
    let (max_quoted, pull_off_quoted) = (number_after("max force "), number_after("pull-off "));
    let (max_run, pull_off_run) =
        (flat["max_force"].as_f64().unwrap() / 1000.0, flat["pull_off_force"].as_f64().unwrap() / 1000.0);
    assert!((max_quoted / max_run - 1.0).abs() < 1e-3, "README quotes {max_quoted} uN, the run {max_run}");
    assert!(
        (pull_off_quoted / pull_off_run - 1.0).abs() < 0.01,
        "README quotes {pull_off_quoted} uN, the run {pull_off_run}"
    );
    assert_eq!(flat["separated"], true);
    let (w, radius) = (1.0, 200.0);
    let ratio = -flat["pull_off_force"].as_f64().unwrap() / (std::f64::consts::PI * w * radius);
    println!("tutorial pull-off: {ratio:.4} pi w R");
    assert!((1.5..2.0).contains(&ratio), "pull-off {ratio} pi w R outside the JKR-DMT range");
}

/// The tutorial composed with a second flat far from the sphere (50 nm): `history.csv` gives
/// each interface its own columns, prefixed by its name, no two alike; the near flat's maximum
/// force is the one-interface tutorial's (within the run-to-run spread of its increments); the
/// far flat is reported as never in contact, and the plots show the first interface.
#[test]
fn two_interfaces_get_their_own_history_columns() {
    let scratch = root().join("target").join("test-out").join("docs-two-interfaces");
    let _ = std::fs::remove_dir_all(&scratch);
    std::fs::create_dir_all(&scratch).unwrap();
    let tutorial = root().join("docs").join("tutorial");
    std::fs::copy(tutorial.join("sphere.geo"), scratch.join("sphere.geo")).unwrap();
    let case = std::fs::read_to_string(tutorial.join("sphere.toml")).unwrap();
    let far = "[[interfaces]]\nname = \"far\"\ntype = \"rigid-flat\"\nsurface = \"surface\"\napproach = 1.0\n\
               amplitude = \"cycle\"\ninitial_gap = 50.0\nlaw = \"lennard-jones\"\n\
               parameters = { w = 1.0, z0 = 0.169 }\n\n[[steps]]";
    let two = case.replacen("[[steps]]", far, 1);
    std::fs::write(scratch.join("two.toml"), two).unwrap();

    let one = run("stiction run docs/tutorial/sphere.toml --out out/one --quiet", &scratch);
    assert!(one.status.success(), "{}", String::from_utf8_lossy(&one.stderr));
    let out = run(&format!("stiction run {}/two.toml --out out/two", scratch.display()), &scratch);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("far: max force") && stdout.contains("never in contact"), "{stdout}");

    let history = std::fs::read_to_string(scratch.join("two").join("history.csv")).unwrap();
    let header: Vec<&str> = history.lines().next().unwrap().split(',').collect();
    let mut unique = header.clone();
    unique.sort();
    unique.dedup();
    assert_eq!(unique.len(), header.len(), "repeated column names: {header:?}");
    for column in ["flat_approach", "flat_force", "flat_contact_area", "far_approach", "far_force"] {
        assert!(header.contains(&column), "no {column} in {header:?}");
    }
    assert!(!header.contains(&"force"), "{header:?}");
    assert!(scratch.join("two").join("force_approach.png").exists());

    let interfaces = |folder: &str| -> serde_json::Value {
        let text = std::fs::read_to_string(scratch.join(folder).join("summary.json")).unwrap();
        serde_json::from_str::<serde_json::Value>(&text).unwrap()["interfaces"].clone()
    };
    let (one, two) = (interfaces("one"), interfaces("two"));
    let max = |v: &serde_json::Value| v["max_force"].as_f64().unwrap();
    assert!((max(&two[0]) / max(&one[0]) - 1.0).abs() < 1e-3, "{} against {}", max(&two[0]), max(&one[0]));
    let far_force = two[1]["most_tensile_force"].as_f64().unwrap();
    assert!(far_force < 0.0 && -far_force < 1e-4 * max(&one[0]), "far flat's force {far_force}");
    assert_eq!(two[1]["separated"], false);
}

/// Every field `summary.json` holds (at the top, per interface, and in its `units` block) is
/// named in the output reference's `summary.json` section, and every name there is a field: the
/// reference cannot fall behind the file, nor describe a field that is gone.
#[test]
fn the_output_reference_names_every_summary_field_and_no_other() {
    use stiction::run::{InterfaceSummary, RunSummary};
    let text = std::fs::read_to_string(root().join("docs/outputs.md")).unwrap();
    let start = text.find("## `summary.json`").expect("a summary.json section");
    let end = text[start + 3..].find("\n## ").map_or(text.len(), |i| start + 3 + i);
    let section = &text[start..end];
    // the names in the first column of its tables: `a`, `b[]`, comma-joined
    let documented: std::collections::BTreeSet<String> = section
        .lines()
        .filter_map(|l| l.strip_prefix("| `"))
        .flat_map(|l| {
            l.split(" |")
                .next()
                .unwrap_or("")
                .split(',')
                .map(|n| n.trim().trim_matches('`').trim_end_matches("[]").to_string())
                .collect::<Vec<_>>()
        })
        .collect();
    let summary = RunSummary { interfaces: vec![InterfaceSummary::default()], ..Default::default() };
    let json = serde_json::to_value(&summary).unwrap();
    let mut fields: std::collections::BTreeSet<String> = json.as_object().unwrap().keys().cloned().collect();
    fields.extend(json["interfaces"][0].as_object().unwrap().keys().cloned());
    let missing: Vec<&String> = fields.iter().filter(|f| !documented.contains(*f)).collect();
    assert!(missing.is_empty(), "summary.json fields not in docs/outputs.md: {missing:?}");
    let stale: Vec<&String> = documented.iter().filter(|d| !fields.contains(*d)).collect();
    assert!(stale.is_empty(), "docs/outputs.md names summary.json fields that do not exist: {stale:?}");
    // the units block's dimensions are listed in its row
    let units_row = section.lines().find(|l| l.starts_with("| `units`")).unwrap();
    for unit in json["units"].as_object().unwrap().keys() {
        assert!(units_row.contains(&format!("`{unit}`")), "the units row does not name `{unit}`");
    }
}

/// The validation report (docs/validation-report.md, written by scripts/validation-report.sh)
/// matches the tests: every test it lists exists in its module, and every validation module
/// that compares through `stiction_tests::validate` has tests in it. (Its numbers are the
/// tests' own, re-measured by running the script; this checks that no test was renamed,
/// removed or added without the report following.)
#[test]
fn the_validation_report_lists_the_tests_that_validate_and_only_those() {
    let report = std::fs::read_to_string(root().join("docs/validation-report.md")).unwrap();
    let listed: Vec<(String, String)> = report
        .lines()
        .filter_map(|l| l.strip_prefix("## `")?.strip_suffix('`'))
        .filter_map(|t| t.split_once("::").map(|(m, f)| (m.to_string(), f.to_string())))
        .collect();
    assert!(!listed.is_empty(), "the report lists no tests");
    let dir = root().join("tests/tests");
    for (module, test) in &listed {
        let source = std::fs::read_to_string(dir.join(format!("{module}.rs")))
            .unwrap_or_else(|_| panic!("the report lists {module}::{test}, but tests/tests/{module}.rs is gone"));
        assert!(
            source.contains(&format!("fn {test}(")),
            "the report lists {module}::{test}, which tests/tests/{module}.rs no longer has: run scripts/validation-report.sh"
        );
    }
    for entry in std::fs::read_dir(&dir).unwrap().flatten() {
        let module = entry.path().file_stem().unwrap().to_string_lossy().to_string();
        let source = std::fs::read_to_string(entry.path()).unwrap();
        if source.contains("validate(") {
            assert!(
                listed.iter().any(|(m, _)| *m == module),
                "tests/tests/{module}.rs validates, but the report has none of its tests: run scripts/validation-report.sh"
            );
        }
    }
}
