"""Placeholder: filled in by the issue that owns this command."""

import click

COMMANDS: list[click.Command] = []
