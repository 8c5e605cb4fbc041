# Thin wrapper: everything lives in make.sh so that it also works where make is not installed.
.PHONY: lab test browser binder site bench install
lab test browser binder site bench install:
	./make.sh $@
