"""The game model for any number of goals: instances, profiles, distances, payoffs."""
