"""The structured route: the game's value and best responses without the walk tree."""
