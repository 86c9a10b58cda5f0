"""Built-in action bundle: closer (manifest.toml and weights live in this folder)."""
