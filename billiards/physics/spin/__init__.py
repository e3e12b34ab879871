"""The spin model: sliding, rolling and spinning balls (docs/spin.md). Its closed-form
motion by state, its contact times, its law and its result."""
