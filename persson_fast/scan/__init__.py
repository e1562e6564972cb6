"""Parameter scans."""
