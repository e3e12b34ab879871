"""The film's sound: the voices, the sound track, the room."""
