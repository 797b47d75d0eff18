"""ddg-oracle reference: exact discrete differential geometry (Bobenko's notes)."""
