# Layer: model. Modules and the objects of the modules each one uses.
MODULES += model
$(OBJDIR)/model.o: $(OBJDIR)/kinds.o $(OBJDIR)/solver_codes.o
