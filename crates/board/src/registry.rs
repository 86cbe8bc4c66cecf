//! The module registry: what each module posts, reads, waits on and answers. The dictionary
//! dependency diagrams are drawn from, and how a query nobody can answer is reported at once.

use rustc_hash::FxHashMap;

/// One module's declaration.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ModuleDecl {
    pub name: String,
    /// Message types it posts.
    pub posts: Vec<String>,
    /// Types it reads without blocking.
    pub reads: Vec<String>,
    /// Labels it queries and waits on.
    pub waits_on: Vec<String>,
    /// Atoms it answers as an expert.
    pub answers: Vec<String>,
}

impl ModuleDecl {
    pub fn new(name: impl Into<String>) -> ModuleDecl {
        ModuleDecl {
            name: name.into(),
            ..ModuleDecl::default()
        }
    }

    pub fn posts<S: Into<String>>(mut self, types: impl IntoIterator<Item = S>) -> Self {
        self.posts.extend(types.into_iter().map(Into::into));
        self
    }

    pub fn reads<S: Into<String>>(mut self, types: impl IntoIterator<Item = S>) -> Self {
        self.reads.extend(types.into_iter().map(Into::into));
        self
    }

    pub fn waits_on<S: Into<String>>(mut self, labels: impl IntoIterator<Item = S>) -> Self {
        self.waits_on.extend(labels.into_iter().map(Into::into));
        self
    }

    pub fn answers<S: Into<String>>(mut self, atoms: impl IntoIterator<Item = S>) -> Self {
        self.answers.extend(atoms.into_iter().map(Into::into));
        self
    }
}

/// Every registered module, by name; re-registering a name replaces its declaration (a module
/// reloaded at run time).
#[derive(Clone, Debug, Default)]
pub struct Registry {
    modules: FxHashMap<String, ModuleDecl>,
}

impl Registry {
    pub fn register(&mut self, decl: ModuleDecl) {
        self.modules.insert(decl.name.clone(), decl);
    }

    pub fn get(&self, name: &str) -> Option<&ModuleDecl> {
        self.modules.get(name)
    }

    /// Modules in name order.
    pub fn modules(&self) -> Vec<&ModuleDecl> {
        let mut all: Vec<_> = self.modules.values().collect();
        all.sort_by(|a, b| a.name.cmp(&b.name));
        all
    }

    pub fn answers(&self, atom: &str) -> bool {
        self.modules
            .values()
            .any(|m| m.answers.iter().any(|a| a == atom))
    }

    /// The modules that answer `atom`, in name order.
    pub fn answerers(&self, atom: &str) -> Vec<&str> {
        let mut names: Vec<&str> = self
            .modules
            .values()
            .filter(|m| m.answers.iter().any(|a| a == atom))
            .map(|m| m.name.as_str())
            .collect();
        names.sort_unstable();
        names
    }

    /// The modules that read or wait on `ty`, in name order.
    pub fn listeners(&self, ty: &str) -> Vec<&str> {
        let mut names: Vec<&str> = self
            .modules
            .values()
            .filter(|m| m.reads.iter().chain(&m.waits_on).any(|t| t == ty))
            .map(|m| m.name.as_str())
            .collect();
        names.sort_unstable();
        names
    }
}
