"""Built-in action bundle: away (manifest.toml and weights live in this folder)."""
