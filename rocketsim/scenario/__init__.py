"""Scenario files: pydantic models, units and YAML loading with precise errors."""
