"""The reproduction report: a scenario's analyses as report.html, figures and tables."""
