# Stands in for a browser test whose tools are missing: fails with MESSAGE.
message(FATAL_ERROR "${MESSAGE}")
