# Thin wrapper: everything lives in make.sh so that it also works where make is not installed.
.PHONY: lab test bench install
lab test bench install:
	./make.sh $@
