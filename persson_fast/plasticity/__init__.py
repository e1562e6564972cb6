"""The yield wall."""
