"""Built-in action bundle: next_to (manifest.toml and weights live in this folder)."""
