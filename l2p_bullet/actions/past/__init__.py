"""Built-in action bundle: past (manifest.toml and weights live in this folder)."""
