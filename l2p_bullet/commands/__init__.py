"""CLI commands, one module per family; each exposes COMMANDS and imports only click at top level."""
