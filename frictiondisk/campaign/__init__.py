"""Campaigns: validated campaign files (spec), and what is built on them."""
