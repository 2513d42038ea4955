"""One adapter module per design kind: spec → synthesis → layup plan → model → fabrication plan."""
