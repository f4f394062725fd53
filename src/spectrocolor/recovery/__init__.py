"""Reflectance recovery: smoothest reflectances (van Trigt), optimal colours, metamers."""
