"""The Processing algorithms of the rock hatching provider."""
