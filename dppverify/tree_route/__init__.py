"""The tree route: the truncated game's walk tree, its LPs and exact best responses."""
