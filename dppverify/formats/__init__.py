"""File formats at the edges: JSON reading, bounded files, MovingAI maps and scenarios."""
