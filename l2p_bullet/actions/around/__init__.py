"""Built-in action bundle: around (manifest.toml and weights live in this folder)."""
