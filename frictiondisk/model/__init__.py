"""What a user writes, validated: scene and campaign schemas (pydantic), layouts, limits.
Lowest layer: imports nothing else of frictiondisk."""
