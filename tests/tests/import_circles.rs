//! No import circle in the tree's Rust code: no file imports, through any
//! chain of others, a file that imports it, and in no folder do its rooms
//! (each file and each subfolder) import each other in a circle, so every
//! folder can be read from the bottom up.
//!
//! A file imports another when it names an item the other defines: in a
//! `use` (tests' included) or a path in its code that starts with
//! `crate::`, `super::`, `self::` or a module the file declares. A name is
//! followed through re-exports to the file that defines it, so a module's
//! `pub use` of its own submodules' items (its face) is no import of its
//! own; any other re-export is. Each crate is read from its roots (the
//! files no `mod` declares); paths inside macro calls are not read.
//!
//! Between crates, the manifests are read: no crate depends on itself
//! through others, dev-dependencies included (which Cargo allows), and the
//! top-level folders the crates live in (kernel/, boot/, xtask/, tests/)
//! depend on each other one way.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use harness::workspace;
use syn::visit::Visit;
use walkdir::WalkDir;

/// One `use` leaf: where it stands, its path, the name it brings in, and
/// whether it is exported (`pub`, `pub(crate)`, ...).
struct UseLeaf {
    module: Vec<String>,
    path: Vec<String>,
    name: String,
    exported: bool,
}

/// What one file holds.
#[derive(Default)]
struct FileItems {
    /// Items defined at the file's top, by name.
    defines: BTreeSet<String>,
    /// Child modules declared without a body (`mod name;`), and their
    /// `#[path]`, if any, by the module they are declared in.
    declares: Vec<(Vec<String>, String, Option<String>)>,
    uses: Vec<UseLeaf>,
    /// Paths in code, each with the module it stands in.
    paths: Vec<(Vec<String>, Vec<String>)>,
}

fn flatten(tree: &syn::UseTree, prefix: &mut Vec<String>, out: &mut Vec<(Vec<String>, String)>) {
    match tree {
        syn::UseTree::Path(path) => {
            prefix.push(path.ident.to_string());
            flatten(&path.tree, prefix, out);
            prefix.pop();
        }
        syn::UseTree::Name(name) => {
            let ident = name.ident.to_string();
            let mut path = prefix.clone();
            if ident != "self" {
                path.push(ident.clone());
            }
            let brought = if ident == "self" { prefix.last().cloned().unwrap_or_default() } else { ident };
            out.push((path, brought));
        }
        syn::UseTree::Rename(rename) => {
            let mut path = prefix.clone();
            if rename.ident != "self" {
                path.push(rename.ident.to_string());
            }
            out.push((path, rename.rename.to_string()));
        }
        syn::UseTree::Glob(_) => out.push((prefix.clone(), "*".to_string())),
        syn::UseTree::Group(group) => {
            for tree in &group.items {
                flatten(tree, prefix, out);
            }
        }
    }
}

/// Collects a file's items, module by module.
struct Reader<'a> {
    items: &'a mut FileItems,
    module: Vec<String>,
}

impl<'ast> Visit<'ast> for Reader<'_> {
    fn visit_item(&mut self, item: &'ast syn::Item) {
        if self.module.is_empty() {
            let name = match item {
                syn::Item::Fn(f) => Some(&f.sig.ident),
                syn::Item::Struct(s) => Some(&s.ident),
                syn::Item::Enum(e) => Some(&e.ident),
                syn::Item::Trait(t) => Some(&t.ident),
                syn::Item::Type(t) => Some(&t.ident),
                syn::Item::Const(c) => Some(&c.ident),
                syn::Item::Static(s) => Some(&s.ident),
                syn::Item::Union(u) => Some(&u.ident),
                syn::Item::Macro(m) => m.ident.as_ref(),
                _ => None,
            };
            if let Some(name) = name {
                self.items.defines.insert(name.to_string());
            }
        }
        match item {
            syn::Item::Mod(module) if module.content.is_none() => {
                let path = module.attrs.iter().find(|a| a.path().is_ident("path")).and_then(|a| match &a.meta {
                    syn::Meta::NameValue(syn::MetaNameValue {
                        value: syn::Expr::Lit(syn::ExprLit { lit: syn::Lit::Str(s), .. }),
                        ..
                    }) => Some(s.value()),
                    _ => None,
                });
                self.items.declares.push((self.module.clone(), module.ident.to_string(), path));
            }
            syn::Item::Mod(module) => {
                self.module.push(module.ident.to_string());
                syn::visit::visit_item_mod(self, module);
                self.module.pop();
            }
            syn::Item::Use(item) => {
                let mut leaves = Vec::new();
                flatten(&item.tree, &mut Vec::new(), &mut leaves);
                let exported = !matches!(item.vis, syn::Visibility::Inherited);
                for (path, name) in leaves {
                    self.items.uses.push(UseLeaf { module: self.module.clone(), path, name, exported });
                }
            }
            _ => syn::visit::visit_item(self, item),
        }
    }

    fn visit_path(&mut self, path: &'ast syn::Path) {
        let segments: Vec<String> = path.segments.iter().map(|s| s.ident.to_string()).collect();
        if segments.len() > 1 && path.leading_colon.is_none() {
            self.items.paths.push((self.module.clone(), segments));
        }
        syn::visit::visit_path(self, path);
    }
}

/// Every Rust file below `root` that the project wrote.
fn rust_files(root: &Path) -> Vec<PathBuf> {
    WalkDir::new(root)
        .into_iter()
        .filter_entry(|entry| !matches!(entry.file_name().to_str(), Some("target" | ".git")))
        .filter_map(|entry| entry.ok())
        .filter(|entry| entry.file_type().is_file() && entry.path().extension().is_some_and(|e| e == "rs"))
        .map(|entry| entry.into_path())
        .collect()
}

/// The file a `mod name;` declared in `module` of `file` is in.
fn declared_file(file: &Path, module: &[String], name: &str, path: Option<&str>) -> Option<PathBuf> {
    let dir = file.parent()?;
    if let Some(path) = path {
        return Some(dir.join(path)).filter(|p| p.is_file());
    }
    let stem = file.file_stem()?.to_string_lossy();
    let own = if matches!(stem.as_ref(), "mod" | "lib" | "main") { dir.to_path_buf() } else { dir.join(&*stem) };
    // A crate root that is not `lib.rs` or `main.rs` (a test, a bench)
    // declares its modules beside itself.
    [own, dir.to_path_buf()].iter().map(|base| module.iter().fold(base.clone(), |b, m| b.join(m))).find_map(|base| {
        [base.join(format!("{name}.rs")), base.join(name).join("mod.rs")].into_iter().find(|p| p.is_file())
    })
}

/// The tree read: every file's items, and every crate's modules.
struct Tree {
    files: BTreeMap<PathBuf, FileItems>,
    /// For each file, its crate root and module path.
    place: BTreeMap<PathBuf, (PathBuf, Vec<String>)>,
    /// For each crate root, its modules' files by module path.
    modules: BTreeMap<PathBuf, BTreeMap<Vec<String>, PathBuf>>,
}

impl Tree {
    fn read(root: &Path) -> Result<Tree> {
        let mut files = BTreeMap::new();
        for file in rust_files(root) {
            let text = std::fs::read_to_string(&file).with_context(|| format!("failed to read {}", file.display()))?;
            let syntax = syn::parse_file(&text).with_context(|| format!("failed to parse {}", file.display()))?;
            let mut items = FileItems::default();
            Reader { items: &mut items, module: Vec::new() }.visit_file(&syntax);
            files.insert(file, items);
        }
        let mut children: BTreeMap<PathBuf, Vec<(Vec<String>, PathBuf)>> = BTreeMap::new();
        let mut declared = BTreeSet::new();
        for (file, items) in &files {
            for (module, name, path) in &items.declares {
                if let Some(child) = declared_file(file, module, name, path.as_deref()) {
                    let mut at = module.clone();
                    at.push(name.clone());
                    children.entry(file.clone()).or_default().push((at, child.clone()));
                    declared.insert(child);
                }
            }
        }
        let mut place = BTreeMap::new();
        let mut modules: BTreeMap<PathBuf, BTreeMap<Vec<String>, PathBuf>> = BTreeMap::new();
        for crate_root in files.keys().filter(|file| !declared.contains(*file)) {
            let mut stack = vec![(crate_root.clone(), Vec::new())];
            while let Some((file, at)) = stack.pop() {
                if place.contains_key(&file) {
                    continue;
                }
                place.insert(file.clone(), (crate_root.clone(), at.clone()));
                modules.entry(crate_root.clone()).or_default().insert(at.clone(), file.clone());
                for (inner, child) in children.get(&file).into_iter().flatten() {
                    stack.push((child.clone(), at.iter().chain(inner).cloned().collect()));
                }
            }
        }
        Ok(Tree { files, place, modules })
    }

    /// The file and the rest of `path`, named from `module` of `file`,
    /// where the path starts in this crate.
    fn module_of(&self, file: &Path, module: &[String], path: &[String]) -> Option<(PathBuf, Vec<String>)> {
        let (crate_root, at) = self.place.get(file)?;
        let modules = &self.modules[crate_root];
        let here: Vec<String> = at.iter().chain(module).cloned().collect();
        let full: Vec<String> = match path.first()?.as_str() {
            "crate" => path[1..].to_vec(),
            "super" | "self" => {
                let mut base = here.clone();
                let mut rest = path;
                while let Some(first) = rest.first().filter(|s| *s == "super" || *s == "self") {
                    if first == "super" {
                        base.pop();
                    }
                    rest = &rest[1..];
                }
                base.into_iter().chain(rest.iter().cloned()).collect()
            }
            first => {
                let child: Vec<String> = here.iter().cloned().chain([first.to_string()]).collect();
                if !modules.contains_key(&child) {
                    return None;
                }
                here.into_iter().chain(path.iter().cloned()).collect()
            }
        };
        (0..=full.len()).rev().find_map(|k| modules.get(&full[..k]).map(|f| (f.clone(), full[k..].to_vec())))
    }

    /// The file that defines what `path` names from `module` of `file`,
    /// following re-exports; `None` outside this crate.
    fn resolve(&self, file: &Path, module: &[String], path: &[String], depth: usize) -> Option<PathBuf> {
        let (target, rest) = self.module_of(file, module, path)?;
        let Some(name) = rest.first().filter(|name| *name != "*") else { return Some(target) };
        let items = &self.files[&target];
        if depth > 16 || items.defines.contains(name) {
            return Some(target);
        }
        let through = items.uses.iter().find(|leaf| leaf.module.is_empty() && &leaf.name == name);
        let followed = through.and_then(|leaf| {
            let onward: Vec<String> = leaf.path.iter().chain(&rest[1..]).cloned().collect();
            self.resolve(&target, &[], &onward, depth + 1)
        });
        Some(followed.unwrap_or(target))
    }

    /// Whether `inner` is `outer` or one of its submodules.
    fn within(&self, inner: &Path, outer: &Path) -> bool {
        match (self.place.get(inner), self.place.get(outer)) {
            (Some((a, inner)), Some((b, outer))) => a == b && inner.starts_with(outer),
            _ => false,
        }
    }

    /// Every import between two files, with a name it is made by.
    fn imports(&self) -> BTreeMap<PathBuf, BTreeMap<PathBuf, String>> {
        let mut imports: BTreeMap<PathBuf, BTreeMap<PathBuf, String>> = BTreeMap::new();
        for (file, items) in self.files.iter().filter(|(file, _)| self.place.contains_key(*file)) {
            let mut add = |target: Option<PathBuf>, how: String| {
                if let Some(target) = target.filter(|target| target != file) {
                    imports.entry(file.clone()).or_default().entry(target).or_insert(how);
                }
            };
            for leaf in &items.uses {
                let target = self.resolve(file, &leaf.module, &leaf.path, 0);
                let face = leaf.exported && target.as_ref().is_some_and(|target| self.within(target, file));
                if !face {
                    add(target, format!("use {}", leaf.path.join("::")));
                }
            }
            for (module, path) in &items.paths {
                add(self.resolve(file, module, path, 0), path.join("::"));
            }
        }
        imports
    }
}

/// The strongly connected components of more than one node (Tarjan).
fn circles<N: Ord + Clone>(edges: &BTreeMap<N, BTreeSet<N>>) -> Vec<Vec<N>> {
    struct State<N> {
        index: BTreeMap<N, usize>,
        low: BTreeMap<N, usize>,
        stack: Vec<N>,
        found: Vec<Vec<N>>,
    }
    fn strong<N: Ord + Clone>(node: &N, edges: &BTreeMap<N, BTreeSet<N>>, state: &mut State<N>) {
        let number = state.index.len();
        state.index.insert(node.clone(), number);
        state.low.insert(node.clone(), number);
        state.stack.push(node.clone());
        for next in edges.get(node).into_iter().flatten() {
            if !state.index.contains_key(next) {
                strong(next, edges, state);
                let low = state.low[node].min(state.low[next]);
                state.low.insert(node.clone(), low);
            } else if state.stack.contains(next) {
                let low = state.low[node].min(state.index[next]);
                state.low.insert(node.clone(), low);
            }
        }
        if state.low[node] == state.index[node] {
            let at = state.stack.iter().position(|n| n == node).expect("on the stack");
            let component: Vec<N> = state.stack.split_off(at);
            if component.len() > 1 {
                state.found.push(component);
            }
        }
    }
    let mut state = State { index: BTreeMap::new(), low: BTreeMap::new(), stack: Vec::new(), found: Vec::new() };
    for node in edges.keys() {
        if !state.index.contains_key(node) {
            strong(node, edges, &mut state);
        }
    }
    state.found
}

/// Every circle of files, and of rooms within a folder where one of the
/// rooms is a folder, each shown with what ties it.
fn circles_in(root: &Path) -> Result<Vec<String>> {
    let tree = Tree::read(root)?;
    let imports = tree.imports();
    let shown = |file: &Path| file.strip_prefix(root).unwrap_or(file).display().to_string();
    let mut report = Vec::new();
    let files: BTreeMap<PathBuf, BTreeSet<PathBuf>> =
        imports.iter().map(|(file, targets)| (file.clone(), targets.keys().cloned().collect())).collect();
    for circle in circles(&files) {
        let ties: Vec<String> = circle
            .iter()
            .flat_map(|a| imports[a].iter().filter(|(b, _)| circle.contains(b)).map(move |(b, how)| (a, b, how)))
            .map(|(a, b, how)| format!("{} -> {} ({how})", shown(a), shown(b)))
            .collect();
        report.push(format!("files: {}", ties.join("; ")));
    }
    let folders: BTreeSet<PathBuf> =
        tree.place.keys().flat_map(|file| file.ancestors().skip(1)).map(Path::to_path_buf).collect();
    for folder in folders.iter().filter(|folder| folder.starts_with(root)) {
        let room = |file: &Path| -> Option<(PathBuf, bool)> {
            let first = file.strip_prefix(folder).ok()?.components().next()?;
            let room = folder.join(first);
            let is_folder = room != file;
            Some((room, is_folder))
        };
        let mut rooms: BTreeMap<(PathBuf, bool), BTreeSet<(PathBuf, bool)>> = BTreeMap::new();
        for (a, targets) in &imports {
            for b in targets.keys() {
                if let (Some(from), Some(to)) = (room(a), room(b)) {
                    if from != to {
                        rooms.entry(from).or_default().insert(to);
                    }
                }
            }
        }
        for circle in circles(&rooms).into_iter().filter(|circle| circle.iter().any(|(_, is_folder)| *is_folder)) {
            let names: Vec<String> = circle
                .iter()
                .map(|(room, is_folder)| format!("{}{}", shown(room), if *is_folder { "/" } else { "" }))
                .collect();
            report.push(format!("rooms of {}/: {}", shown(folder), names.join(" <-> ")));
        }
    }
    Ok(report)
}

#[test]
fn no_file_and_no_folder_imports_itself_in_a_circle() -> Result<()> {
    let root = workspace::root();
    let tree = Tree::read(root)?;
    let imports: usize = tree.imports().values().map(BTreeMap::len).sum();
    assert!(tree.place.len() > 200 && imports > 300, "{} files, {imports} imports read", tree.place.len());
    let found = circles_in(root)?;
    assert!(found.is_empty(), "{} import circles:\n{}", found.len(), found.join("\n"));
    Ok(())
}

/// Writes `files` (path, text) under a fresh folder.
fn made_up(files: &[(&str, &str)]) -> Result<tempfile::TempDir> {
    let dir = tempfile::tempdir()?;
    for (path, text) in files {
        let path = dir.path().join(path);
        std::fs::create_dir_all(path.parent().expect("a file in a folder"))?;
        std::fs::write(path, text)?;
    }
    Ok(dir)
}

#[test]
fn a_circle_of_files_or_of_folders_is_caught_and_a_face_is_not_one() -> Result<()> {
    // A face re-exporting its children, whose child uses the crate root:
    // no circle.
    let faces = made_up(&[
        ("src/lib.rs", "mod a;\nmod b;\npub use a::A;\npub struct Root;\n"),
        ("src/a.rs", "use crate::Root;\npub struct A(Root);\n"),
        ("src/b.rs", "pub fn b() -> crate::A { todo!() }\n"),
    ])?;
    assert_eq!(circles_in(faces.path())?, Vec::<String>::new());
    // Two files through a use and a path in code; two folders through
    // their files.
    let tangled = made_up(&[
        ("src/lib.rs", "mod a;\nmod b;\nmod p;\nmod q;\n"),
        ("src/a.rs", "use crate::b::B;\npub struct A;\n"),
        ("src/b.rs", "pub struct B;\nfn f() { let _ = super::a::A; }\n"),
        ("src/p/mod.rs", "mod x;\npub use x::X;\n"),
        ("src/p/x.rs", "pub struct X(crate::q::Y);\n"),
        ("src/q/mod.rs", "mod y;\npub use y::Y;\nuse crate::p::X;\n"),
        ("src/q/y.rs", "pub struct Y;\n"),
    ])?;
    let found = circles_in(tangled.path())?;
    assert_eq!(found.len(), 2, "{found:?}");
    assert!(found[0].starts_with("files: src/a.rs -> src/b.rs (use crate::b::B); src/b.rs -> src/a.rs"), "{found:?}");
    assert_eq!(found[1], "rooms of src/: src/p/ <-> src/q/");
    Ok(())
}

/// The workspace's crates, read from the manifests under `root`: each
/// crate's name, its folder, and the workspace crates it depends on, in
/// any of its dependency tables (normal, dev, build, and each target's).
fn crates(root: &Path) -> Result<BTreeMap<String, (PathBuf, BTreeSet<String>)>> {
    let read = |path: &Path| -> Result<toml::Table> {
        let text = std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
        toml::from_str(&text).with_context(|| format!("parsing {}", path.display()))
    };
    let workspace = read(&root.join("Cargo.toml"))?;
    let members: Vec<PathBuf> = workspace["workspace"]["members"]
        .as_array()
        .context("the workspace's members")?
        .iter()
        .filter_map(|member| member.as_str().map(PathBuf::from))
        .collect();
    let manifests: Vec<(PathBuf, toml::Table)> = members
        .iter()
        .map(|member| Ok((member.clone(), read(&root.join(member).join("Cargo.toml"))?)))
        .collect::<Result<_>>()?;
    let name_at: BTreeMap<PathBuf, String> = manifests
        .iter()
        .filter_map(|(member, manifest)| {
            Some((member.clone(), manifest.get("package")?.get("name")?.as_str()?.to_string()))
        })
        .collect();
    // A dependency's folder: its own `path`, or the workspace's entry's.
    let shared = workspace["workspace"].get("dependencies").and_then(toml::Value::as_table);
    let folder_of = |member: &Path, key: &str, spec: &toml::Value| -> Option<PathBuf> {
        if let Some(path) = spec.get("path").and_then(toml::Value::as_str) {
            return Some(normalized(&member.join(path)));
        }
        let inherited = spec.get("workspace").and_then(toml::Value::as_bool) == Some(true);
        inherited.then(|| shared?.get(key)?.get("path")?.as_str().map(PathBuf::from)).flatten()
    };
    let mut crates = BTreeMap::new();
    for (member, manifest) in &manifests {
        let Some(name) = name_at.get(member) else { continue };
        let targets = manifest.get("target").and_then(toml::Value::as_table).into_iter().flat_map(|t| t.values());
        let tables = std::iter::once(manifest).chain(targets.filter_map(toml::Value::as_table));
        let mut depends = BTreeSet::new();
        for table in tables {
            for kind in ["dependencies", "dev-dependencies", "build-dependencies"] {
                for (key, spec) in table.get(kind).and_then(toml::Value::as_table).into_iter().flatten() {
                    if let Some(other) = folder_of(member, key, spec).and_then(|folder| name_at.get(&folder)) {
                        depends.insert(other.clone());
                    }
                }
            }
        }
        crates.insert(name.clone(), (member.clone(), depends));
    }
    Ok(crates)
}

/// `path` with its `..` and `.` taken out.
fn normalized(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for part in path.components() {
        match part {
            std::path::Component::ParentDir => {
                out.pop();
            }
            std::path::Component::CurDir => {}
            other => out.push(other),
        }
    }
    out
}

/// Every circle of crates (Cargo refuses one of normal dependencies, not
/// one through a dev-dependency), and of the top-level folders the crates
/// live in, each shown with its members.
fn crate_circles_in(root: &Path) -> Result<Vec<String>> {
    let crates = crates(root)?;
    let edges: BTreeMap<String, BTreeSet<String>> =
        crates.iter().map(|(name, (_, depends))| (name.clone(), depends.clone())).collect();
    let mut report: Vec<String> =
        circles(&edges).into_iter().map(|circle| format!("crates: {}", circle.join(" <-> "))).collect();
    let top = |name: &String| -> String {
        let folder = &crates[name].0;
        folder.components().next().map_or(String::new(), |first| first.as_os_str().to_string_lossy().into_owned())
    };
    let mut folders: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (name, depends) in &edges {
        for other in depends.iter().filter(|other| top(other) != top(name)) {
            folders.entry(top(name)).or_default().insert(top(other));
        }
    }
    for circle in circles(&folders) {
        let ties: Vec<String> = edges
            .iter()
            .flat_map(|(name, depends)| depends.iter().map(move |other| (name, other)))
            .filter(|(name, other)| {
                top(name) != top(other) && circle.contains(&top(name)) && circle.contains(&top(other))
            })
            .map(|(name, other)| format!("{name} ({}/) -> {other} ({}/)", top(name), top(other)))
            .collect();
        report.push(format!("top-level folders: {}; through {}", circle.join(" <-> "), ties.join(", ")));
    }
    Ok(report)
}

#[test]
fn no_crate_and_no_top_level_folder_depends_on_itself_in_a_circle() -> Result<()> {
    let root = workspace::root();
    let crates = crates(root)?;
    let depends: usize = crates.values().map(|(_, depends)| depends.len()).sum();
    assert!(crates.len() > 10 && depends > 20, "{} crates, {depends} dependencies read", crates.len());
    let found = crate_circles_in(root)?;
    assert!(found.is_empty(), "{} circles:\n{}", found.len(), found.join("\n"));
    Ok(())
}

#[test]
fn a_circle_of_crates_or_of_top_level_folders_is_caught() -> Result<()> {
    let manifest =
        |name: &str, dependencies: &str| format!("[package]\nname = \"{name}\"\nversion = \"0.1.0\"\n\n{dependencies}");
    let workspace = "[workspace]\nmembers = [\"low/a\", \"low/b\", \"high/c\"]\n\n\
                     [workspace.dependencies]\na = { path = \"low/a\" }\nc = { path = \"high/c\" }\n";
    // a (low/) depends on b (low/) by path; c (high/) on a, and a
    // dev-depends on c: a circle of crates through a dev-dependency, and
    // of the folders low/ and high/.
    let tangled = made_up(&[
        ("Cargo.toml", workspace),
        (
            "low/a/Cargo.toml",
            &manifest("a", "[dependencies]\nb = { path = \"../b\" }\n\n[dev-dependencies]\nc.workspace = true\n"),
        ),
        ("low/b/Cargo.toml", &manifest("b", "")),
        ("high/c/Cargo.toml", &manifest("c", "[target.'cfg(unix)'.dependencies]\na.workspace = true\n")),
    ])?;
    let found = crate_circles_in(tangled.path())?;
    assert_eq!(
        found,
        ["crates: a <-> c", "top-level folders: high <-> low; through a (low/) -> c (high/), c (high/) -> a (low/)"],
        "{found:?}"
    );
    // Without the dev-dependency: one way.
    let one_way = made_up(&[
        ("Cargo.toml", workspace),
        ("low/a/Cargo.toml", &manifest("a", "[dependencies]\nb = { path = \"../b\" }\n")),
        ("low/b/Cargo.toml", &manifest("b", "")),
        ("high/c/Cargo.toml", &manifest("c", "[target.'cfg(unix)'.dependencies]\na.workspace = true\n")),
    ])?;
    assert_eq!(crate_circles_in(one_way.path())?, Vec::<String>::new());
    Ok(())
}
