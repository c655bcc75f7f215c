//! Where an output came from: the commit of the checkout a command ran in.

/// `git describe --always --dirty --abbrev=12` of the current directory's checkout (a
/// `-dirty` suffix when it had uncommitted changes), or a sentence saying it is unknown.
pub fn git_commit() -> String {
    std::process::Command::new("git")
        .args(["describe", "--always", "--dirty", "--abbrev=12"])
        .output()
        .ok()
        .filter(|o| o.status.success())
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map(|s| s.trim().to_string())
        .unwrap_or_else(|| "unknown (not run in a git checkout)".into())
}
