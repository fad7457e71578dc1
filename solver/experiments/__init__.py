"""The paper's Section VI experiments."""
