"""Shared test helpers: closed-form references written independently of the package."""
