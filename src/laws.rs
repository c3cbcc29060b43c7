//! Interface-law lookup. Built-in laws are linked statically and used through the same C ABI
//! as plugins; other laws are found by name on the plugin search path, or loaded from an
//! explicit library path:
//! 1. directories listed in the case's `plugin_path` (relative to the case file);
//! 2. directories in the environment variable `STICTION_PLUGIN_PATH` (separated by ':');
//! 3. the directory of the `stiction` executable (where `cargo build` puts workspace plugins).
//!
//! A parameter named `penalty` whose value is 0 is replaced by 100 E / h (E: the stiffest
//! material's modulus, h: the interface's mean face size).

use std::path::{Path, PathBuf};
use std::sync::{Arc, OnceLock};
use stiction_core::interface_law::{InterfaceLaw, resolve_parameters};
use stiction_interfaces::plugin::LawLibrary;
use stiction_law_sdk::abi::DescriptorHolder;

/// Context a law may need for defaults.
pub struct LawContext {
    /// Largest stiffness scale (Young's modulus) of the materials.
    pub modulus: f64,
    /// Typical face size of the interface surface.
    pub face_size: f64,
}

/// Descriptors of the statically linked laws, built once per process. Built-in laws go
/// through the same C functions as plugins.
fn builtin_holders() -> &'static [DescriptorHolder] {
    static HOLDERS: OnceLock<Vec<DescriptorHolder>> = OnceLock::new();
    HOLDERS.get_or_init(|| {
        vec![
            DescriptorHolder::new::<stiction_law_frictionless_contact::FrictionlessContact>(),
            DescriptorHolder::new::<stiction_law_lennard_jones::LennardJones>(),
            DescriptorHolder::new::<stiction_law_ru_asperity::RuAsperity>(),
            DescriptorHolder::new::<stiction_law_cohesive_zone::CohesiveZone>(),
            DescriptorHolder::new::<stiction_law_hertz_asperity::HertzAsperity>(),
        ]
    })
}

/// Built-in and discoverable laws.
pub struct LawRegistry {
    builtin: Vec<Arc<LawLibrary>>,
    search_dirs: Vec<PathBuf>,
}

fn shared_library(path: &Path) -> bool {
    matches!(path.extension().and_then(|e| e.to_str()), Some("so" | "dylib" | "dll"))
}

impl LawRegistry {
    /// The registry with the built-in laws and the search path (case directories first).
    pub fn new(case_dirs: &[PathBuf]) -> Self {
        let builtin = builtin_holders()
            .iter()
            // SAFETY: the holders live in a process-wide static.
            .map(|h| {
                Arc::new(unsafe { LawLibrary::from_static(h.descriptor()) }.expect("built-in laws match the host ABI"))
            })
            .collect();
        let mut search_dirs: Vec<PathBuf> = case_dirs.to_vec();
        if let Some(env) = std::env::var_os("STICTION_PLUGIN_PATH") {
            search_dirs.extend(std::env::split_paths(&env));
        }
        if let Some(dir) = std::env::current_exe().ok().and_then(|e| e.parent().map(Path::to_path_buf)) {
            search_dirs.push(dir);
        }
        // a folder named twice (STICTION_PLUGIN_PATH and the executable's own, or a case's) is
        // searched once: otherwise every law in it would be found twice and refused as ambiguous
        let mut seen = std::collections::HashSet::new();
        search_dirs.retain(|d| seen.insert(d.canonicalize().unwrap_or_else(|_| d.clone())));
        Self { builtin, search_dirs }
    }

    pub fn builtin(&self) -> &[Arc<LawLibrary>] {
        &self.builtin
    }
    pub fn search_dirs(&self) -> &[PathBuf] {
        &self.search_dirs
    }

    /// Every shared library on the search path, opened (or the reason it could not be).
    pub fn discover(&self) -> Vec<(PathBuf, Result<Arc<LawLibrary>, String>)> {
        let mut found = Vec::new();
        for dir in &self.search_dirs {
            let Ok(entries) = std::fs::read_dir(dir) else { continue };
            let mut paths: Vec<PathBuf> =
                entries.filter_map(|e| e.ok().map(|e| e.path())).filter(|p| shared_library(p)).collect();
            paths.sort();
            for p in paths {
                let r = LawLibrary::open(&p).map(Arc::new).map_err(|e| e.to_string());
                found.push((p, r));
            }
        }
        found
    }

    /// A law by name (built-in first, then the search path) or by library path.
    pub fn find(&self, name_or_path: &str, base: &Path) -> Result<Arc<LawLibrary>, String> {
        let as_path = Path::new(name_or_path);
        if shared_library(as_path) || name_or_path.contains('/') {
            let p = if as_path.is_absolute() { as_path.to_path_buf() } else { base.join(as_path) };
            return LawLibrary::open(&p).map(Arc::new).map_err(|e| e.to_string());
        }
        if let Some(l) = self.builtin.iter().find(|l| l.name == name_or_path) {
            return Ok(l.clone());
        }
        let mut problems = Vec::new();
        let mut matches: Vec<(PathBuf, Arc<LawLibrary>)> = Vec::new();
        for (path, r) in self.discover() {
            // the first directory that holds the law wins; within it, the name must be unique
            if matches.first().is_some_and(|(first, _)| first.parent() != path.parent()) {
                break;
            }
            match r {
                Ok(l) if l.name == name_or_path => matches.push((path, l)),
                Ok(_) => {}
                // a plugin of the wanted name may be the one with the wrong ABI: say so
                Err(e) if e.contains("ABI version") || e.contains("bytes, expected") => problems.push(e),
                Err(_) => {}
            }
        }
        match matches.len() {
            0 => {}
            1 => return Ok(matches.remove(0).1),
            _ => {
                let paths: Vec<String> = matches.iter().map(|(p, _)| format!("'{}'", p.display())).collect();
                return Err(format!(
                    "{} libraries declare the law '{name_or_path}': {}; give the one you mean by its path (law = \"path/to/lib.so\")",
                    matches.len(),
                    paths.join(" and ")
                ));
            }
        }
        let builtin: Vec<&str> = self.builtin.iter().map(|l| l.name.as_str()).collect();
        let dirs: Vec<String> = self.search_dirs.iter().map(|d| d.display().to_string()).collect();
        let mut msg = format!(
            "no interface law '{name_or_path}': not built in ({}) and not found in the plugin search path [{}] (set STICTION_PLUGIN_PATH or the case's plugin_path, or give the library's path)",
            builtin.join(", "),
            dirs.join(", ")
        );
        for p in problems {
            msg.push_str(&format!("; {p}"));
        }
        Err(msg)
    }
}

/// Creates a law instance from its parameters (validated against the law's parameter list)
/// and, for laws that take one, the text of a configuration file (e.g. a calibration).
pub fn make_law(
    registry: &LawRegistry,
    name: &str,
    base: &Path,
    given: &[(String, f64)],
    config_file: Option<&Path>,
    context: &LawContext,
) -> Result<Arc<dyn InterfaceLaw>, String> {
    let library = registry.find(name, base)?;
    let config = match (config_file, &library.config_description) {
        (Some(path), Some(_)) => {
            let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read '{}': {e}", path.display()))?;
            Some((path, text))
        }
        (None, Some(what)) => return Err(format!("law '{}' needs a config_file: {what}", library.name)),
        (Some(path), None) => {
            return Err(format!("law '{}' takes no config_file, but '{}' was given", library.name, path.display()));
        }
        (None, None) => None,
    };
    let mut values = resolve_parameters(&library.name, &library.parameters, given)?;
    for (spec, v) in library.parameters.iter().zip(values.iter_mut()) {
        if spec.name == "penalty" && *v == 0.0 {
            *v = 100.0 * context.modulus / context.face_size;
        }
    }
    let text = config.as_ref().map(|(_, t)| t.as_str()).unwrap_or("");
    let law = library.instantiate(&values, text).map_err(|e| match &config {
        Some((path, _)) => format!("{e} (config file '{}')", path.display()),
        None => e.to_string(),
    })?;
    Ok(Arc::new(law))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The same folder given twice, once through a `..` detour, is searched once, in its first
    /// place; the executable's folder is searched last unless named before.
    #[test]
    fn a_folder_named_twice_is_searched_once() {
        let dir = std::env::temp_dir().join(format!("stiction-laws-dedup-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        let detour = dir.join("sub").join("..");
        let registry = LawRegistry::new(&[dir.clone(), detour, dir.clone()]);
        let named: Vec<&PathBuf> =
            registry.search_dirs().iter().filter(|d| d.canonicalize().ok() == dir.canonicalize().ok()).collect();
        assert_eq!(named, vec![&dir]);
        assert_eq!(registry.search_dirs()[0], dir);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
