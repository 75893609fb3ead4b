"""The mechanisms of the book's source studies, one module each."""
