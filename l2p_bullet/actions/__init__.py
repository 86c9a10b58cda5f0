"""Built-in action bundles; each subpackage folder holds manifest.toml and weights."""
